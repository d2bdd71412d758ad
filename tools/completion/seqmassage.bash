# bash completion for seqmassage (installed as share/bash-completion/completions/seqmassage).
# Commands and options are read from the program's own --help (so they cannot go stale); config
# files are *.json, meshes *.obj/*.ply/*.off, output folders directories.

_seqmassage_words() {  # the options listed by `seqmassage [COMMAND] --help`
  "$1" ${2:+"$2"} --help 2>/dev/null | grep -oE -- '(^|[ ,])--?[a-zA-Z][a-zA-Z-]*' |
    sed -E 's/^[ ,]//' | sort -u
}

_seqmassage_commands() {  # the names in the "Commands:" block of `seqmassage --help`
  "$1" --help 2>/dev/null |
    sed -nE '/^Commands:/,/^$/{s/^  ([a-z]+) .*/\1/p}' | sort -u
}

_seqmassage() {
  local cur prev words cword
  if declare -F _init_completion >/dev/null; then
    _init_completion || return
  else
    cur="${COMP_WORDS[COMP_CWORD]}"
    prev="${COMP_WORDS[COMP_CWORD - 1]}"
    words=("${COMP_WORDS[@]}")
    cword=$COMP_CWORD
  fi
  local program="${words[0]}" command="" i
  for ((i = 1; i < cword; i++)); do
    case "${words[i]}" in
      -*) ;;
      *)
        if _seqmassage_commands "$program" | grep -qx -- "${words[i]}"; then
          command="${words[i]}"
        fi
        break
        ;;
    esac
  done

  case "$prev" in
    --threads | --frames | --shard | --spacing | --feature-angle) return ;;
    --csv | --json)
      COMPREPLY=($(compgen -f -- "$cur"))
      return
      ;;
    --template)
      COMPREPLY=($(compgen -f -X '!*.@(obj|ply|off|OBJ|PLY|OFF)' -- "$cur") $(compgen -d -- "$cur"))
      return
      ;;
    --complete)
      COMPREPLY=($(compgen -f -X '!*.json' -- "$cur") $(compgen -d -- "$cur"))
      return
      ;;
  esac

  if [[ "$cur" == -* ]]; then
    COMPREPLY=($(compgen -W "$(_seqmassage_words "$program" "$command")" -- "$cur"))
    return
  fi
  case "$command" in
    "")
      COMPREPLY=($(compgen -W "$(_seqmassage_commands "$program")" -- "$cur")
        $(compgen -f -X '!*.json' -- "$cur") $(compgen -d -- "$cur"))
      ;;
    merge) COMPREPLY=($(compgen -d -- "$cur")) ;;
    measure)
      COMPREPLY=($(compgen -f -X '!*.@(obj|ply|off|OBJ|PLY|OFF)' -- "$cur") $(compgen -d -- "$cur"))
      ;;
    config) ;;
  esac
  [[ ${#COMPREPLY[@]} -eq 1 && -d "${COMPREPLY[0]}" ]] && compopt -o nospace 2>/dev/null
  return 0
}
complete -F _seqmassage -o filenames seqmassage
