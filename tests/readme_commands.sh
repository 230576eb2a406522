#!/usr/bin/env bash
# The README's commands still exist and still parse:
# - every command behind a headline figure (the "[n] ..." lines): each program it runs from
#   build/ exists and accepts the command line (SNAPFIT_PARSE_ONLY=1: options and values
#   checked, nothing run); each script it runs exists and knows the options given to it;
# - every row of the tool's table: the subcommand exists and its --help lists each option.
# Usage: readme_commands.sh SOURCE_DIR BUILD_DIR
set -uo pipefail
src=$1
build=$(cd "$2" && pwd)
readme=$src/README.md
failures=0
fail() {
  echo "README.md: $*" >&2
  failures=$((failures + 1))
}

# The footnotes of the headline table, continuation lines joined, "[n] " and comments cut.
footnotes=$(awk '/^## Headline figures/ { on = 1 } on && /^## / && !/Headline/ { on = 0 } on' "$readme" |
  sed -e ':a' -e '/\\$/N; s/\\\n[[:space:]]*/ /; ta' | grep -E '^\[[0-9]+\] ' | sed -E 's/[[:space:]]+# .*$//')
[ -n "$footnotes" ] || fail "no '[n] command' lines under '## Headline figures'"

checked=0
while IFS= read -r line; do
  tag=${line%%]*}]
  command=${line#*] }
  # A command may wrap others (bash -c '...', env settings): split it into its simple commands.
  while IFS= read -r part; do
    read -r -a words <<<"$part"
    # Leading environment settings (HOME=$(mktemp -d), CI=true) are not the program.
    while ((${#words[@]})) && [[ ${words[0]} == *=* ]]; do words=("${words[@]:1}"); done
    ((${#words[@]})) || continue
    case ${words[0]} in
      bash)
        # bash SCRIPT [--option...]: the script exists and its text names each option.
        script=${words[1]:-}
        [ "$script" = "-c" ] && continue
        if [ ! -f "$src/$script" ]; then
          fail "$tag runs '$script', which does not exist"
          continue
        fi
        for w in "${words[@]:2}"; do
          [[ $w == --* ]] && ! grep -qe "$w)" "$src/$script" && fail "$tag: $script does not take $w"
        done
        checked=$((checked + 1))
        ;;
      ./build/*)
        program=$build/${words[0]#./build/}
        if [ ! -x "$program" ]; then
          fail "$tag runs '${words[0]}', which the build does not make"
          continue
        fi
        if ! out=$(cd "$src" && SNAPFIT_PARSE_ONLY=1 "$program" "${words[@]:1}" 2>&1); then
          fail "$tag: '${words[*]}' no longer parses: $out"
        fi
        checked=$((checked + 1))
        ;;
      python3 | */python3)
        # python3 SCRIPT: the script exists.
        if [ ! -f "$src/${words[1]:-}" ]; then
          fail "$tag runs the Python script '${words[1]:-}', which does not exist"
          continue
        fi
        checked=$((checked + 1))
        ;;
      *) ;;  # shell plumbing (mpirun, cd) around the commands checked above
    esac
  done < <(printf '%s\n' "$command" | sed -E "s/\\\$\([^)]*\)/X/g; s/bash -c '//; s/'\$//; s/ (&&|;|\|\|) /\n/g")
done <<<"$footnotes"
echo "checked $checked commands behind the headline figures"

# The tool's table: "| `[mpirun -np N] snapfit SUB [--option ...]` | what it does |".
rows=0
while IFS= read -r synopsis; do
  sub=$(sed -E 's/^.*snapfit ([a-z-]+).*$/\1/' <<<"$synopsis")
  if ! help=$("$build/snapfit" "$sub" --help 2>&1); then
    fail "the tool's table lists 'snapfit $sub', which the tool does not have"
    continue
  fi
  for option in $(grep -oE -- '--[a-z][a-z-]*' <<<"$synopsis" | sort -u); do
    grep -qe "$option\b" <<<"$help" || fail "the tool's table gives 'snapfit $sub $option', which its --help does not list"
  done
  rows=$((rows + 1))
done < <(awk '/^## The tool/ { on = 1; next } on && /^## / { on = 0 } on' "$readme" |
  grep -oE '^\| `[^`]*snapfit [a-z-]+[^`]*`' | sed -E 's/^\| `//; s/`$//')
echo "checked $rows rows of the tool's table"
((rows > 0)) || fail "no 'snapfit SUBCOMMAND' rows under '## The tool'"

((failures == 0)) || exit 1
