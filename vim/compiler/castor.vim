" Vim compiler file: castor --check, so that :make fills the quickfix list
" Use: :compiler castor   then   :make
if exists("current_compiler")
  finish
endif
let current_compiler = "castor"

if exists(":CompilerSet") != 2
  command -nargs=* CompilerSet setlocal <args>
endif

CompilerSet makeprg=castor\ --check\ %:S
" FILE:LINE:COL: error|warning|note: MESSAGE, then the source line and a caret (ignored)
CompilerSet errorformat=%f:%l:%c:\ %trror:\ %m,%f:%l:%c:\ %tarning:\ %m,%f:%l:%c:\ %tote:\ %m,%-G\ %.%#,%-Gcastor:\ %.%#
