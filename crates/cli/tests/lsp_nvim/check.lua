-- Neovim's built-in LSP client against `aster lsp` (headless): opens the
-- command file given in $ASTER_LSP_FILE, waits for the server's
-- diagnostics and writes them, one per line, to $ASTER_LSP_OUT as
-- `line:col severity code: message` (1-based line, 0-based byte column as
-- Neovim reports them), then quits. Works with Neovim 0.7 (Debian 12) and
-- later. Driven by crates/cli/tests/lsp_nvim.rs.
local file = os.getenv("ASTER_LSP_FILE")
local out = os.getenv("ASTER_LSP_OUT")
local aster = os.getenv("ASTER_BIN")

vim.cmd("edit " .. vim.fn.fnameescape(file))
local buf = vim.api.nvim_get_current_buf()
local client = vim.lsp.start_client({
  name = "aster",
  cmd = { aster, "lsp" },
  root_dir = vim.fn.fnamemodify(file, ":h"),
})
vim.lsp.buf_attach_client(buf, client)

local ok = vim.wait(20000, function()
  return #vim.diagnostic.get(buf) > 0
end, 50)

local lines = {}
if not ok then
  table.insert(lines, "no diagnostics within 20 s")
end
local diags = vim.diagnostic.get(buf)
table.sort(diags, function(a, b)
  if a.lnum ~= b.lnum then return a.lnum < b.lnum end
  return a.col < b.col
end)
for _, d in ipairs(diags) do
  local first = vim.split(d.message, "\n")[1]
  table.insert(lines, string.format("%d:%d %s %s: %s", d.lnum + 1, d.col,
    vim.diagnostic.severity[d.severity], tostring(d.code), first))
end
vim.fn.writefile(lines, out)
vim.lsp.stop_client(client)
vim.wait(2000, function() return vim.lsp.client_is_stopped(client) end, 50)
vim.cmd("qall!")
