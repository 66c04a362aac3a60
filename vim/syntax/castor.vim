" Vim syntax file for the Castor scene language (.cas)
if exists("b:current_syntax")
  finish
endif

syn keyword castorTodo contained TODO FIXME XXX NOTE
syn region castorComment start="/\*" end="\*/" contains=castorTodo
syn match castorComment "//.*$" contains=castorTodo
syn match castorPreProc "^\s*#\s*\(include\|define\|undef\|ifdef\|ifndef\|if\|elif\|else\|endif\|line\|error\|pragma\)\>.*$"

" unknown primitives show as errors; the known ones, matched after, win
syn match castorError "![a-z][A-Za-z0-9_]*"
syn match castorPrimitive "!\(cu\|sp\|cy\|co\|to\|pr\|py\|we\|ex\|rv\)\>"
syn match castorTransform "@\(t\|rx\|ry\|rz\|r\|h\|m\|f\|s\)\>"
syn match castorBoolean "\$[UID]\>"
syn match castorFacetize "^\s*>"
syn match castorParameter "\<[A-Z][A-Za-z0-9_]*\>"
syn keyword castorConstant PI TOLERANCE
syn keyword castorFunction sin cos tan asin acos atan atan2 sqrt abs exp log floor ceil round min max
syn match castorNumber "\<\d\+\(\.\d*\)\=\([eE][+-]\=\d\+\)\=\>"
syn match castorNumber "\.\d\+\([eE][+-]\=\d\+\)\="

hi def link castorTodo Todo
hi def link castorComment Comment
hi def link castorPreProc PreProc
hi def link castorPrimitive Type
hi def link castorError Error
hi def link castorTransform Statement
hi def link castorBoolean Operator
hi def link castorFacetize Special
hi def link castorParameter Identifier
hi def link castorConstant Constant
hi def link castorFunction Function
hi def link castorNumber Number

let b:current_syntax = "castor"
