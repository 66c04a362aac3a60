-- castor --lsp with Neovim's built-in client (vim.lsp.start_client, Neovim 0.7+).
local M = { clients = {} }

-- The workspace of a buffer: the topmost of the folders, from the buffer's own
-- upwards, that hold *.cas files (so that a part in bus_shelter/ is analysed
-- with the scene beside that folder that #includes it), as autoload/castor.vim
-- finds it for Vim; vim.g.castor_lsp_root, if set, is the workspace.
function M.root_of(buffer)
  if vim.g.castor_lsp_root then
    return vim.fn.fnamemodify(vim.g.castor_lsp_root, ':p'):gsub('/$', '')
  end
  local name = vim.api.nvim_buf_get_name(buffer)
  local root = name == '' and vim.fn.getcwd() or vim.fn.fnamemodify(name, ':p:h')
  while true do
    local parent = vim.fn.fnamemodify(root, ':h')
    if parent == root or #vim.fn.glob(parent .. '/*.cas', true, true) == 0 then
      return root
    end
    root = parent
  end
end

function M.attach(buffer)
  local root = M.root_of(buffer)
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
