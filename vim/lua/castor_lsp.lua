-- castor --lsp with Neovim's built-in client (vim.lsp.start_client, Neovim 0.7+).
local M = { clients = {} }

-- The folder of the buffer's file: the workspace the server accepts documents from.
local function root_of(buffer)
  local name = vim.api.nvim_buf_get_name(buffer)
  if name == '' then
    return vim.fn.getcwd()
  end
  return vim.fn.fnamemodify(name, ':p:h')
end

function M.attach(buffer)
  local root = vim.g.castor_lsp_root or root_of(buffer)
  local id = M.clients[root]
  if id == nil or vim.lsp.get_client_by_id(id) == nil then
    id = vim.lsp.start_client({
      name = 'castor',
      cmd = vim.g.castor_lsp_command or { 'castor', '--lsp' },
      root_dir = root,
      workspace_folders = { { uri = vim.uri_from_fname(root), name = root } },
    })
    M.clients[root] = id
  end
  if id ~= nil then
    vim.lsp.buf_attach_client(buffer, id)
  end
  return id
end

return M
