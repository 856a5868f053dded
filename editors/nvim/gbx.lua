-- .gbx support for Neovim 0.8+: filetype, comments and the gbx language server (`gbxc lsp`).
--
-- Load it in one of two ways:
--   * copy this file to ~/.config/nvim/plugin/gbx.lua (Neovim runs it at start-up), or
--   * copy it to ~/.config/nvim/lua/gbx.lua and add `require('gbx')` to init.lua.
-- The server binary is `gbxc` on PATH; to use another one, set it before loading:
--   vim.g.gbx_server_path = '/path/to/build/gbxc'

vim.filetype.add({ extension = { gbx = 'gbx' } })

local group = vim.api.nvim_create_augroup('gbx', { clear = true })

vim.api.nvim_create_autocmd('FileType', {
  group = group,
  pattern = 'gbx',
  callback = function(args)
    local buf = args.buf
    vim.bo[buf].commentstring = '// %s'
    vim.bo[buf].comments = 's1:/*,mb:*,ex:*/,://'
    vim.bo[buf].omnifunc = 'v:lua.vim.lsp.omnifunc' -- <C-x><C-o> asks the server

    local server = vim.g.gbx_server_path or 'gbxc'
    if vim.fn.executable(server) ~= 1 then
      vim.notify_once('gbx: "' .. server .. '" not found; no language server', vim.log.levels.WARN)
      return
    end

    -- The project root: the nearest folder above the file that holds `.git`, else the
    -- file's own folder.
    local file = vim.api.nvim_buf_get_name(buf)
    local dir = file ~= '' and vim.fs.dirname(file) or vim.fn.getcwd()
    local git = vim.fs.find('.git', { path = dir, upward = true })[1]
    local root = git and vim.fs.dirname(git) or dir

    -- One client per root: vim.lsp.start reuses a running client of the same name and root.
    vim.lsp.start({
      name = 'gbx',
      cmd = { server, 'lsp' },
      root_dir = root,
    })
  end,
})
