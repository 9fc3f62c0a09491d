# The reading of doc/build_times.txt (`key = value` lines, written by tools/measure_commands.sh), shared
# by tools/readme.sh (the README's sentence) and tools/build_times_tex.sh (the article's values), so that
# both state the same times alike. Each runs
#   awk -F' = ' -f tools/build_times.awk -f PROGRAM doc/build_times.txt
# with its own END block, which reads value[KEY] and calls the functions below.
/^#/ { next }
{ value[$1] = $2 }

# A duration in seconds as a person reads it: 170.4 -> "2 min 50 s", 58.3 -> "58 s", 1.23 -> "1.2 s".
# Rounded to whole seconds before it is split into minutes, so that 179.6 s reads 3 min 0 s (not 2 min
# 60 s); up to 60 s in seconds, below 9.95 s to a tenth.
function duration(s,    r) {
  if (s < 9.95) return sprintf("%.1f s", s)
  r = int(s + 0.5)
  if (r > 60) return sprintf("%d min %d s", int(r / 60), r % 60)
  return sprintf("%d s", r)
}

# A command's time: its one value, or "median (min DASH max)" for several runs.
function span(key, dash,    v, n) {
  n = split(value[key], v, " ")
  return n == 1 ? duration(v[1]) : duration(v[2]) " (" duration(v[1]) " " dash " " duration(v[3]) ")"
}

# 1 if the file has every key of a measured run; else 0, after a line on standard error naming the
# program (who) and the first key missing.
function complete(who,    keys, k) {
  split("date commit cpu cores runs own_cpu_seconds other_cpu_seconds make_all_seconds make_test_seconds make_all_again_seconds", keys, " ")
  for (k in keys) if (!(keys[k] in value)) {
    print who ": the build times lack " keys[k] " (tools/measure_commands.sh writes it)" > "/dev/stderr"
    return 0
  }
  return 1
}
