// VS Code client for the gbx language server.
//
// Highlighting, comments and brackets come from the grammar and the language
// configuration in package.json. Everything else (diagnostics, hover, completion,
// go to definition, document symbols, formatting) comes from the compiler itself:
// this file starts `<gbx.serverPath> lsp` and talks LSP to it over stdin/stdout.
'use strict';

const path = require('path');
const vscode = require('vscode');
const { LanguageClient } = require('vscode-languageclient/node');

/** @type {LanguageClient | undefined} */
let client;

// The `gbx.serverPath` setting: a bare name (`gbxc`) is looked up on PATH, an absolute
// path is used as is, and a relative path (`build/gbxc`) is taken from the first
// workspace folder.
function serverCommand() {
  const configured = vscode.workspace.getConfiguration('gbx').get('serverPath') || 'gbxc';
  const folders = vscode.workspace.workspaceFolders;
  const hasSeparator = configured.includes('/') || configured.includes('\\');
  if (hasSeparator && !path.isAbsolute(configured) && folders && folders.length > 0) {
    return path.join(folders[0].uri.fsPath, configured);
  }
  return configured;
}

async function startClient() {
  const command = serverCommand();
  // No `transport` field: the client then talks over the child's stdin/stdout without
  // adding a `--stdio` argument, so the command line is exactly `<command> lsp`.
  const server = { command, args: ['lsp'] };
  client = new LanguageClient(
    'gbx', // also the prefix of the `gbx.trace.server` setting
    'gbx language server',
    { run: server, debug: server },
    {
      documentSelector: [
        { scheme: 'file', language: 'gbx' },
        { scheme: 'untitled', language: 'gbx' },
      ],
    },
  );
  try {
    await client.start();
  } catch (err) {
    client = undefined;
    vscode.window.showErrorMessage(
      `gbx: could not start "${command} lsp" (${err && err.message ? err.message : err}). ` +
        'Set "gbx.serverPath" to the gbxc binary.',
    );
  }
}

async function stopClient() {
  const running = client;
  client = undefined;
  if (running) await running.stop();
}

function activate(context) {
  // A changed server path takes effect at once: stop the old server, start the new one.
  context.subscriptions.push(
    vscode.workspace.onDidChangeConfiguration(async (event) => {
      if (event.affectsConfiguration('gbx.serverPath')) {
        await stopClient();
        await startClient();
      }
    }),
  );
  return startClient();
}

function deactivate() {
  return stopClient();
}

module.exports = { activate, deactivate };
