" Castor scene files
autocmd BufRead,BufNewFile *.cas setfiletype castor
