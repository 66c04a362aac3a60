" The workspace of a *.cas buffer, for every client of castor --lsp: the
" topmost of the folders, from the buffer's own upwards, that hold *.cas files
" (so that a part in bus_shelter/ is analysed with the scene beside that
" folder that #includes it). g:castor_lsp_root, if set, is the workspace.
function! castor#root(buffer) abort
  if exists('g:castor_lsp_root')
    return fnamemodify(g:castor_lsp_root, ':p:s?/$??')
  endif
  let l:name = bufname(a:buffer)
  let l:root = empty(l:name) ? getcwd() : fnamemodify(l:name, ':p:h')
  while 1
    let l:parent = fnamemodify(l:root, ':h')
    if l:parent ==# l:root || empty(glob(l:parent . '/*.cas', 1, 1))
      return l:root
    endif
    let l:root = l:parent
  endwhile
endfunction

" The command that starts the server.
function! castor#command() abort
  return get(g:, 'castor_lsp_command', ['castor', '--lsp'])
endfunction
