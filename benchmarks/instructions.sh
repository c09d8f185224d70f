# Sourced by the callgrind scripts: `instructions CMD...` prints the instructions CMD executes
# (callgrind's PROGRAM TOTALS; load-independent).
instructions() {
    local out
    out=$(mktemp)
    valgrind --tool=callgrind --callgrind-out-file="$out" "$@" >/dev/null 2>&1
    callgrind_annotate "$out" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}'
    rm -f "$out"
}
