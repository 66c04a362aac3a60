" A small client of castor --lsp for Vim 9 as Debian ships it (no language
" client installed): the server's diagnostics as signs and in the location
" list, updated as one types; its messages (the live preview's address under
" castor --lsp --serve) echoed; the edits it asks for (workspace/applyEdit: a
" gesture made on the preview) made in the buffers, unsaved, undone with u.
" With yegappan/lsp, vim-lsp or ALE installed, plugin/castor_lsp.vim hands the
" server to them instead.
let s:servers = {}  " root -> {job, channel, ready, waiting}
let s:versions = {}  " buffer number -> version sent
let s:diagnostics = {}  " buffer number -> the last diagnostics as location list items
let s:messages = []  " the server's window/showMessage texts

function! s:Uri(path) abort
  return 'file://' . substitute(fnamemodify(a:path, ':p'), '[^A-Za-z0-9/._~-]',
        \ '\=printf("%%%02X", char2nr(submatch(0)))', 'g')
endfunction

function! s:Path(uri) abort
  return substitute(substitute(a:uri, '^file://', '', ''), '%\(\x\x\)',
        \ '\=nr2char(str2nr(submatch(1), 16))', 'g')
endfunction

function! s:Text(buffer) abort
  return join(getbufline(a:buffer, 1, '$'), "\n") . "\n"
endfunction

" Start (once per workspace) and attach the buffer.
function! castor#client#attach(buffer) abort
  let l:root = castor#root(a:buffer)
  if !has_key(s:servers, l:root)
    let s:servers[l:root] = s:Start(l:root)
  endif
  let l:server = s:servers[l:root]
  if get(l:server, 'failed', 0)
    return
  endif
  call setbufvar(a:buffer, 'castor_root', l:root)
  if l:server.ready
    call s:Open(l:server, a:buffer)
  else
    call add(l:server.waiting, a:buffer)
  endif
  execute 'augroup castor_client_' . a:buffer
  autocmd!
  execute 'autocmd TextChanged,TextChangedI <buffer=' . a:buffer . '> call s:Changed(' . a:buffer . ')'
  execute 'autocmd BufWritePost <buffer=' . a:buffer . '> call s:Notify(' . a:buffer . ', "textDocument/didSave")'
  execute 'autocmd BufUnload <buffer=' . a:buffer . '> call s:Notify(' . a:buffer . ', "textDocument/didClose")'
  augroup END
endfunction

function! s:Start(root) abort
  let l:server = #{ready: 0, waiting: []}
  let l:server.job = job_start(castor#command(), #{in_mode: 'lsp', out_mode: 'lsp',
        \ err_io: 'null', out_cb: function('s:Received'), noblock: 1})
  if job_status(l:server.job) !=# 'run'
    echohl WarningMsg
    echomsg 'castor: cannot start ' . join(castor#command()) . ' (is castor installed?)'
    echohl None
    let l:server.failed = 1
    return l:server
  endif
  let l:server.channel = job_getchannel(l:server.job)
  let l:folder = [#{uri: s:Uri(a:root), name: a:root}]
  call ch_sendexpr(l:server.channel, #{method: 'initialize', params: #{processId: getpid(),
        \ rootUri: s:Uri(a:root), workspaceFolders: l:folder,
        \ capabilities: #{workspace: #{applyEdit: v:true}}}},
        \ #{callback: function('s:Initialized', [l:server])})
  return l:server
endfunction

function! s:Initialized(server, channel, answer) abort
  call ch_sendexpr(a:channel, #{method: 'initialized', params: {}})
  let a:server.ready = 1
  for l:buffer in a:server.waiting
    call s:Open(a:server, l:buffer)
  endfor
  let a:server.waiting = []
endfunction

function! s:Open(server, buffer) abort
  let s:versions[a:buffer] = 1
  call ch_sendexpr(a:server.channel, #{method: 'textDocument/didOpen', params: #{textDocument:
        \ #{uri: s:Uri(bufname(a:buffer)), languageId: 'castor', version: 1,
        \ text: s:Text(a:buffer)}}})
endfunction

function! s:Server(buffer) abort
  let l:server = get(s:servers, getbufvar(a:buffer, 'castor_root', ''), {})
  return get(l:server, 'ready', 0) && has_key(s:versions, a:buffer) ? l:server : {}
endfunction

function! s:Changed(buffer) abort
  let l:server = s:Server(a:buffer)
  if empty(l:server)
    return
  endif
  let s:versions[a:buffer] += 1
  call ch_sendexpr(l:server.channel, #{method: 'textDocument/didChange', params: #{
        \ textDocument: #{uri: s:Uri(bufname(a:buffer)), version: s:versions[a:buffer]},
        \ contentChanges: [#{text: s:Text(a:buffer)}]}})
endfunction

function! s:Notify(buffer, method) abort
  let l:server = s:Server(a:buffer)
  if empty(l:server)
    return
  endif
  call ch_sendexpr(l:server.channel, #{method: a:method, params: #{
        \ textDocument: #{uri: s:Uri(bufname(a:buffer))}}})
  if a:method ==# 'textDocument/didClose'
    call remove(s:versions, a:buffer)
  endif
endfunction

function! s:Received(channel, message) abort
  let l:method = get(a:message, 'method', '')
  if l:method ==# 'textDocument/publishDiagnostics'
    call s:Show(a:message.params)
  elseif l:method ==# 'window/showMessage'
    call add(s:messages, a:message.params.message)
    echomsg a:message.params.message
  elseif l:method ==# 'workspace/applyEdit' && has_key(a:message, 'id')
    call s:Answer(a:channel, a:message.id, s:Apply(a:message.params.edit))
  endif
endfunction

" The answer to a request of the server, written whole: Vim 9.0's lsp mode
" refuses the string ids that pygls gives its requests (E475).
function! s:Answer(channel, id, result) abort
  let l:body = json_encode(#{jsonrpc: '2.0', id: a:id, result: a:result})
  call ch_sendraw(a:channel, 'Content-Length: ' . len(l:body) . "\r\n\r\n" . l:body)
endfunction

" workspace/applyEdit: each file's edits, the last in the text first, made in
" its buffer (loaded if it is not), unsaved; the server told of the new text.
function! s:Apply(edit) abort
  try
    for [l:uri, l:edits] in items(get(a:edit, 'changes', {}))
      let l:buffer = bufadd(s:Path(l:uri))
      call bufload(l:buffer)
      for l:e in sort(copy(l:edits), {a, b -> s:Compare(b.range.start, a.range.start)})
        call s:Replace(l:buffer, l:e.range, l:e.newText)
      endfor
      call s:Changed(l:buffer)
    endfor
  catch
    return #{applied: v:false, failureReason: v:exception}
  endtry
  return #{applied: v:true}
endfunction

function! s:Compare(p, q) abort
  return a:p.line != a:q.line ? a:p.line - a:q.line : a:p.character - a:q.character
endfunction

" One TextEdit: the lines of its range replaced by the text they become.
function! s:Replace(buffer, range, text) abort
  let l:count = getbufinfo(a:buffer)[0].linecount
  let l:first = a:range.start.line + 1
  let l:last = min([a:range.end.line + 1, l:count])
  let l:lines = l:first <= l:last ? getbufline(a:buffer, l:first, l:last) : []
  let l:head = strcharpart(get(l:lines, 0, ''), 0, a:range.start.character)
  let l:tail = a:range.end.line + 1 <= l:count
        \ ? strcharpart(getbufline(a:buffer, a:range.end.line + 1)[0], a:range.end.character) : ''
  let l:new = split(l:head . a:text . l:tail, "\n", 1)
  if a:range.end.line + 1 > l:count && len(l:new) > 1 && l:new[-1] ==# ''
    call remove(l:new, -1)  " the text's last line end: Vim writes it itself
  endif
  let l:old = max([l:last - l:first + 1, 0])
  let l:same = min([l:old, len(l:new)])
  if l:same > 0
    call setbufline(a:buffer, l:first, l:new[: l:same - 1])
  endif
  if len(l:new) > l:old
    call appendbufline(a:buffer, l:first + l:old - 1, l:new[l:old :])
  elseif l:old > len(l:new)
    call deletebufline(a:buffer, l:first + len(l:new), l:first + l:old - 1)
  endif
endfunction

" The diagnostics of one file: signs, and the location list of its windows.
function! s:Show(params) abort
  let l:buffer = bufnr(s:Path(a:params.uri))
  if l:buffer < 0
    return
  endif
  let l:items = []
  for l:d in a:params.diagnostics
    call add(l:items, #{bufnr: l:buffer, lnum: l:d.range.start.line + 1,
          \ col: l:d.range.start.character + 1, text: l:d.message,
          \ type: get(l:d, 'severity', 1) == 1 ? 'E' : 'W'})
  endfor
  let s:diagnostics[l:buffer] = l:items
  call sign_unplace('castor', #{buffer: l:buffer})
  call sign_placelist(map(copy(l:items), {_, i -> #{buffer: l:buffer, group: 'castor',
        \ lnum: i.lnum, name: i.type ==# 'E' ? 'CastorError' : 'CastorWarning'}}))
  for l:window in win_findbuf(l:buffer)
    call setloclist(l:window, [], 'r', #{title: 'castor', items: l:items})
  endfor
endfunction

" The diagnostics last shown for a buffer (for scripts and tests).
function! castor#client#diagnostics(buffer) abort
  return get(s:diagnostics, a:buffer, [])
endfunction

" The messages the server showed (the live preview's address).
function! castor#client#messages() abort
  return copy(s:messages)
endfunction

function! castor#client#servers() abort
  return len(s:servers)
endfunction

call sign_define('CastorError', #{text: 'E>', texthl: 'Error'})
call sign_define('CastorWarning', #{text: 'W>', texthl: 'WarningMsg'})
