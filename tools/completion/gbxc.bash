# Bash completion of gbxc: commands, options, formats, .gbx files, and after --gearbox the
# gearboxes of the spec on the command line.

_gbxc_gearboxes() {
  local f=$1
  [[ -r $f ]] || return
  sed -n 's/^[[:space:]]*gearbox[[:space:]]\{1,\}\([A-Za-z_][A-Za-z0-9_]*\).*/\1/p' "$f"
}

_gbxc() {
  local cur prev cmd spec i
  cur=${COMP_WORDS[COMP_CWORD]}
  prev=${COMP_WORDS[COMP_CWORD-1]}
  local commands="solve check dump test fmt lsp help"
  cmd=
  for ((i = 1; i < COMP_CWORD; i++)); do
    case ${COMP_WORDS[i]} in
      solve|check|dump|test|fmt|lsp|help) cmd=${COMP_WORDS[i]}; break ;;
    esac
  done
  case $prev in
    --format)
      if [[ $cmd == check ]]; then COMPREPLY=($(compgen -W "text json" -- "$cur"))
      else COMPREPLY=($(compgen -W "text json csv md html" -- "$cur")); fi
      return ;;
    --gearbox)
      for ((i = 1; i < COMP_CWORD; i++)); do
        [[ ${COMP_WORDS[i]} == *.gbx ]] && spec=${COMP_WORDS[i]}
      done
      spec=${spec/#\~/$HOME}
      COMPREPLY=($(compgen -W "$(_gbxc_gearboxes "$spec")" -- "$cur"))
      return ;;
    -o) COMPREPLY=($(compgen -d -- "$cur")); return ;;
    --jobs|-j|--max-designs|--time-limit) return ;;
  esac
  if [[ -z $cmd ]]; then
    COMPREPLY=($(compgen -W "$commands --help --version" -- "$cur"))
    return
  fi
  local opts
  case $cmd in
    solve) opts="--format --gearbox -o --jobs --max-designs --time-limit --quiet --no-timings --help" ;;
    check) opts="--format --help" ;;
    dump) opts="ast ir --help" ;;
    test) opts="--update --timings --jobs --help" ;;
    fmt) opts="--check --help" ;;
    help) COMPREPLY=($(compgen -W "solve check dump test fmt lsp" -- "$cur")); return ;;
    *) opts="--help" ;;
  esac
  if [[ $cur == -* || $cmd == dump && $prev == dump ]]; then
    COMPREPLY=($(compgen -W "$opts" -- "$cur"))
    return
  fi
  COMPREPLY=($(compgen -f -X '!*.gbx' -- "$cur") $(compgen -d -- "$cur"))
}
complete -o filenames -F _gbxc gbxc
