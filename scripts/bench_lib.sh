# Helpers the benchmark scripts share (sourced, not run): the load average now, and from a
# `/usr/bin/time -v` report the wall time (s) and peak resident memory (GiB); from a .mess file the
# seconds spent in every run of a command.
load() { cut -d' ' -f1 /proc/loadavg; }
wall() { awk '/Elapsed \(wall clock\)/ { n = split($NF, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; printf "%.2f", s }' "$1"; }
rss() { awk '/Maximum resident/ { printf "%.2f", $NF / 1048576 }' "$1"; }
cmd_time() { awk -v c="$2" '$0 ~ "# End of command #[0-9]+ " c " " { s += $(NF - 1) } END { printf "%.2f", s }' "$1"; }
