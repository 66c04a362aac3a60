" castor --lsp for *.cas files in Vim 9: yegappan/lsp and vim-lsp.
" (ALE: ale_linters/castor/castor_lsp.vim; Neovim: plugin/castor_lsp.lua.)
" The command can be changed with  let g:castor_lsp_command = ['castor', '--lsp']
if exists('g:loaded_castor_lsp') || has('nvim')
  finish
endif
let g:loaded_castor_lsp = 1

function! s:Command() abort
  return get(g:, 'castor_lsp_command', ['castor', '--lsp'])
endfunction

" yegappan/lsp: LspAddServer() exists once the plugin is loaded
function! s:Yegappan() abort
  if exists('*LspAddServer')
    let l:command = s:Command()
    call LspAddServer([#{name: 'castor', filetype: ['castor'],
          \ path: l:command[0], args: l:command[1:]}])
  endif
endfunction

augroup castor_lsp
  autocmd!
  autocmd VimEnter * call s:Yegappan()
  " vim-lsp (prabirshrestha/vim-lsp)
  autocmd User lsp_setup call lsp#register_server(#{name: 'castor',
        \ cmd: {server_info -> s:Command()}, allowlist: ['castor']})
augroup END
