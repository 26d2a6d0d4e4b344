# Completes a command line in an interactive zsh on a pseudo terminal and prints the matches, one a
# line (the zsh completion tests: completions_test.cpp).
# Usage: zsh -f zsh_complete.zsh FPATH_DIR 'clmarch render --sa'
zmodload zsh/zpty
zpty shell zsh -f -i
zpty -w shell "fpath=(${(q)1} \$fpath); autoload -Uz compinit; compinit -u -D"
zpty -w shell 'PROMPT=; RPROMPT=; unsetopt zle_bracketed_paste'
# Every match the completion functions add, printed as it is added.
zpty -w shell 'compadd() { local -a hits; builtin compadd -O hits "$@"; print -rl -- "<hit>"${^hits}; builtin compadd "$@" }'
zpty -w shell "print '<ready>'"
zpty -r shell line '*<ready>*'
# zle reads what follows the tab only once the completion is done.
zpty -n -w shell "$2"$'\t'
zpty -w shell $'\C-u'"print '<done>'"
zpty -r shell out '*<done>*<done>*'
print -r -- "$out" | grep -ao '<hit>[^[:cntrl:]]*' | sed 's/<hit>//' | sort -u
zpty -d shell
