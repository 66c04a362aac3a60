" ALE: castor --lsp as the linter of *.cas files (diagnostics, hover, go to definition)
call ale#linter#Define('castor', {
\   'name': 'castor_lsp',
\   'lsp': 'stdio',
\   'executable': {buffer -> get(g:, 'castor_lsp_command', ['castor'])[0]},
\   'command': {buffer -> join(map(copy(get(g:, 'castor_lsp_command', ['castor', '--lsp'])),
\                                  'ale#Escape(v:val)'))},
\   'project_root': {buffer -> castor#root(buffer)},
\})
