" castor --lsp for *.cas files in Vim 9: handed to yegappan/lsp, vim-lsp or ALE
" when one is installed, else started by castor's own small client
" (autoload/castor/client.vim: diagnostics as signs and in the location list).
" (ALE: ale_linters/castor/castor_lsp.vim; Neovim: plugin/castor_lsp.lua.)
" The command can be changed with  let g:castor_lsp_command = ['castor', '--lsp']
" and the workspace with  let g:castor_lsp_root = '/path/to/the/scene/folder'.
if exists('g:loaded_castor_lsp') || has('nvim')
  finish
endif
let g:loaded_castor_lsp = 1

" Another language client, to which the server is handed instead.
function! s:OtherClient() abort
  return exists('*LspAddServer') || exists('g:lsp_loaded') || exists('g:loaded_ale')
endfunction

" yegappan/lsp: LspAddServer() exists once the plugin is loaded
function! s:Yegappan() abort
  if exists('*LspAddServer')
    let l:command = castor#command()
    call LspAddServer([#{name: 'castor', filetype: ['castor'],
          \ path: l:command[0], args: l:command[1:]}])
  endif
endfunction

function! s:Builtin(buffer) abort
  if get(g:, 'castor_lsp_builtin', 1) && !s:OtherClient() && has('channel') && has('job')
    call castor#client#attach(a:buffer)
  endif
endfunction

augroup castor_lsp
  autocmd!
  autocmd VimEnter * call s:Yegappan()
  " vim-lsp (prabirshrestha/vim-lsp)
  autocmd User lsp_setup call lsp#register_server(#{name: 'castor',
        \ cmd: {server_info -> castor#command()}, allowlist: ['castor'],
        \ root_uri: {server_info -> 'file://' . castor#root(bufnr())}})
  autocmd FileType castor call s:Builtin(str2nr(expand('<abuf>')))
augroup END
