#pragma once
// `gbxc lsp`: a Language Server Protocol 3.17 server over a byte stream (stdin/stdout),
// JSON-RPC 2.0 with Content-Length framing, on the same front end as `gbxc check`.
#include <iosfwd>

namespace gbx::lsp {

// Serves until `exit` or the end of `in`. Returns the exit status LSP asks for: 0 when
// `shutdown` came before `exit`, 1 otherwise.
int serve(std::istream& in, std::ostream& out);

} // namespace gbx::lsp
