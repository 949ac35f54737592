#!/usr/bin/env bash
# Runs every chapter at full resolution and prints a summary table.  Called by the `figures`
# target (chapters/CMakeLists.txt), which passes the chapter executables and directories:
#
#   run-chapters.sh --figures DIR --log DIR [--tries EXE --source DIR] [--plot-demo EXE]
#                   [--chapter EXE NN-name]...
#
# For each chapter it runs `EXE --output FIGURES/NN-name` with standard output captured in
# FIGURES/NN-name/output.txt (the "real console output" that the documentation shows).
# Standard error goes to the terminal when there is one (the chapters' progress lines), otherwise
# to LOG/NN-name.stderr.txt, whose end is shown if the chapter fails.
#
# Each chapter writes FIGURES/NN-name/summary.txt (app::Chapter::summary): lines `key = value`.
# The table shows, per chapter: the status, the PNGs written during the run, the wall time, and
# the value of the `error` key (the error against the reference, where the chapter has one).
# The table is also written to LOG/summary.txt; FIGURES/summary.txt holds one row per chapter
# from the chapters' own summaries (the last full run of each).
# The exit status is 1 if any chapter failed.
#
# "What to try" runs: with --tries (the tool docs/quoted_numbers.cpp builds) and --source (the
# chapters' source directory), each chapter is followed by the runs its "What to try" section
# quotes numbers from: `EXE --output LOG/try/NN-name/SLUG OPTIONS`, standard output kept in
# FIGURES/NN-name/try/SLUG.txt, so that the test of quoted numbers can check the text against
# them.  Their figures are not kept, and a run whose checks fail (as some are meant to) is not a
# failure of the chapter.
#
# SPH_ONLY="01 04-monaghan" (environment) runs only the chapters whose names start so.
set -uo pipefail

figures=""
log=""
plot_demo=""
tries=""
source_dir=""
exes=()
dirs=()
while (($#)); do
  case "$1" in
    --figures) figures="$2"; shift 2 ;;
    --log) log="$2"; shift 2 ;;
    --plot-demo) plot_demo="$2"; shift 2 ;;
    --tries) tries="$2"; shift 2 ;;
    --source) source_dir="$2"; shift 2 ;;
    --chapter) exes+=("$2"); dirs+=("$3"); shift 3 ;;
    *) echo "run-chapters.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
if [[ -z "$figures" || -z "$log" ]]; then
  echo "usage: run-chapters.sh --figures DIR --log DIR [--plot-demo EXE] [--chapter EXE DIR]..." >&2
  exit 2
fi
mkdir -p "$figures" "$log"

# ---- Helpers -----------------------------------------------------------------------------------
now() { date +%s.%N; }
# Seconds as people read them: 0.42 s, 12.3 s, 4 min 05 s.
duration() {
  awk -v s="$1" 'BEGIN {
    if (s < 10) printf "%.2f s", s; else if (s < 60) printf "%.1f s", s;
    else if (s < 3600) printf "%d min %02d s", int(s / 60), int(s) % 60;
    else printf "%d h %02d min", int(s / 3600), int(s / 60) % 60 }'
}
# The value of `key` in a summary.txt ("key = value" lines), or empty.
summary_value() {
  [[ -f "$2" ]] && sed -n "s/^$1 = //p" "$2" | tail -n 1
}
selected() {
  [[ -z "${SPH_ONLY:-}" ]] && return 0
  local prefix
  for prefix in $SPH_ONLY; do [[ "$1" == "$prefix"* ]] && return 0; done
  return 1
}
live_stderr=false
[[ -t 2 ]] && live_stderr=true

rows=()           # "name|status|figures|time|error"
extra_figure=""   # a figure written outside the output directory (the plot demo's)
failures=0

# Runs one program: run NAME OUTDIR COMMAND...  (standard output to OUTDIR/output.txt)
run() {
  local name="$1" out="$2"
  shift 2
  mkdir -p "$out"
  rm -f "$out/summary.txt"
  local stamp="$log/$name.stamp" errlog="$log/$name.stderr.txt"
  touch "$stamp"
  sleep 0.01   # so that files written by the run are strictly newer than the stamp
  local start status
  start=$(now)
  if $live_stderr; then
    "$@" > "$out/output.txt"
  else
    "$@" > "$out/output.txt" 2> "$errlog"
  fi
  status=$?
  local seconds
  seconds=$(awk -v a="$start" -v b="$(now)" 'BEGIN { print b - a }')
  local count
  count=$(find "$out" -maxdepth 1 -name '*.png' -newer "$stamp" | wc -l)
  if [[ -n "$extra_figure" && -f "$extra_figure" && "$extra_figure" -nt "$stamp" ]]; then
    count=$((count + 1))
  fi
  local error
  error=$(summary_value error "$out/summary.txt")

  local verdict="ok"
  if ((status != 0)); then
    failures=$((failures + 1))
    local checks
    checks=$(summary_value checks "$out/summary.txt")
    if ((status == 1)) && [[ "$checks" =~ [1-9][0-9]*\ failed ]]; then
      verdict="checks failed"
    elif ((status > 128)); then
      verdict="killed (signal $((status - 128)))"
    else
      verdict="failed (exit $status)"
    fi
    if ! $live_stderr && [[ -s "$errlog" ]]; then
      echo "---- $name: the end of its standard error ($errlog) ----"
      tail -n 20 "$errlog"
      echo "----"
    fi
  fi
  printf '  %-28s %-16s %3d figures  %s\n' "$name" "$verdict" "$count" "$(duration "$seconds")"
  rows+=("$name|$verdict|$count|$(duration "$seconds")|${error:-}")
}

# The "What to try" runs of one chapter: run_tries NAME EXE
run_tries() {
  local name="$1" exe="$2" slug options
  rm -rf "${figures:?}/$name/try" "${log:?}/try/$name"
  while IFS=$'\t' read -r slug options; do
    [[ -n "$slug" ]] || continue
    mkdir -p "$figures/$name/try" "$log/try/$name"
    local start seconds status
    start=$(now)
    # (the options are split as the shell splits words: they are the text's own, e.g. --alpha 0)
    # shellcheck disable=SC2086
    "$exe" --output "$log/try/$name/$slug" $options > "$figures/$name/try/$slug.txt" \
      2> "$log/try/$name/$slug.stderr.txt"
    status=$?
    seconds=$(awk -v a="$start" -v b="$(now)" 'BEGIN { print b - a }')
    printf '    what to try: %-40s exit %d  %s\n' "$options" "$status" "$(duration "$seconds")"
  done < <("$tries" tries "$source_dir/$name")
}

# ---- Run the chapters ----------------------------------------------------------------------------
total=${#exes[@]}
echo "Running ${total} chapter(s) at full resolution into $figures"
for ((i = 0; i < total; i++)); do
  dir="${dirs[$i]}"
  selected "$dir" || continue
  echo "[$((i + 1))/$total] ${exes[$i]} --output $figures/$dir"
  run "$dir" "$figures/$dir" "${exes[$i]}" --output "$figures/$dir"
  [[ -n "$tries" && -d "$source_dir/$dir" ]] && run_tries "$dir" "${exes[$i]}"
done
if [[ -n "$plot_demo" ]] && selected plot-demo; then
  echo "[plot demo] $plot_demo $figures/plot-demo.png"
  # Its figure lives in the figures directory itself; its output stays in the log directory.
  extra_figure="$figures/plot-demo.png"
  run plot-demo "$log/plot-demo" "$plot_demo" "$figures/plot-demo.png"
  extra_figure=""
fi

# ---- The table -----------------------------------------------------------------------------------
{
  printf '\n%-28s  %-16s  %7s  %11s  %s\n' "chapter" "status" "figures" "wall time" \
    "error against the reference"
  printf '%-28s  %-16s  %7s  %11s  %s\n' "----------------------------" "----------------" \
    "-------" "-----------" "---------------------------"
  for row in "${rows[@]}"; do
    IFS='|' read -r name verdict count time error <<< "$row"
    printf '%-28s  %-16s  %7s  %11s  %s\n' "$name" "$verdict" "$count" "$time" "${error:--}"
  done
  if ((${#rows[@]} == 0)); then
    echo "(no chapters)"
  fi
  echo
  if ((failures > 0)); then
    echo "$failures program(s) failed."
  else
    echo "All ${#rows[@]} program(s) ran; figures and output.txt are in $figures/NN-name/."
  fi
} > "$log/summary.txt"
cat "$log/summary.txt"
# The table in the figures directory describes every chapter's figures as they are now: it is
# rebuilt from each chapter's own FIGURES/NN-name/summary.txt (written by the run that drew its
# figures), so running a selection updates its rows and never leaves the others' stale.
{
  printf '\n%-28s  %-16s  %7s  %11s  %s\n' "chapter" "status" "figures" "wall time" \
    "error against the reference"
  printf '%-28s  %-16s  %7s  %11s  %s\n' "----------------------------" "----------------" \
    "-------" "-----------" "---------------------------"
  for dir in "${dirs[@]}"; do
    summary="$figures/$dir/summary.txt"
    if [[ ! -f "$summary" ]]; then
      printf '%-28s  %-16s  %7s  %11s  %s\n' "$dir" "not run" "-" "-" "-"
      continue
    fi
    checks=$(summary_value checks "$summary")
    verdict="ok"
    [[ "$checks" =~ [1-9][0-9]*\ failed ]] && verdict="checks failed"
    [[ "$(summary_value mode "$summary")" == "full" ]] || verdict="not full"
    count=$(find "$figures/$dir" -maxdepth 1 -name '*.png' | wc -l)
    seconds=$(summary_value run_time "$summary" | sed 's/ s$//')
    error=$(summary_value error "$summary")
    printf '%-28s  %-16s  %7s  %11s  %s\n' "$dir" "$verdict" "$count" \
      "$(duration "${seconds:-0}")" "${error:--}"
  done
  echo
  echo "Each row is the chapter's last run at full resolution (figures/NN-name/summary.txt)."
} > "$figures/summary.txt"

((failures == 0))
