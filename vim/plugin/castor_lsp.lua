-- Neovim (0.7 and later): start castor --lsp with Neovim's own client for
-- every buffer of filetype castor (*.cas), one server per folder.
-- The command can be changed with  vim.g.castor_lsp_command = {'castor', '--lsp'}
if vim.g.loaded_castor_lsp_lua then
  return
end
vim.g.loaded_castor_lsp_lua = true

vim.api.nvim_create_autocmd('FileType', {
  group = vim.api.nvim_create_augroup('castor_lsp', { clear = true }),
  pattern = 'castor',
  callback = function(event)
    require('castor_lsp').attach(event.buf)
  end,
})
