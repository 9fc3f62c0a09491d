# style.gp: what every figure of the report shares; each script loads it first, from its own
# directory (load dir.'style.gp' with dir taken from ARG0), after setting `data`.
#
#   - The report's typeface. The report is set in Computer Modern; the figures use its OpenType form,
#     Latin Modern (Debian's fonts-lmodern, which tools/deps.sh requires): text in LM Roman, variables
#     in its italic ({/:Italic t}), Greek letters from Latin Modern Math (lambda_ below).
#   - One colour per mass, the same in every figure: Mod 1 red, Mod 2 blue, Mod 3 green, the
#     consistent mass purple; the exact solution black.
#   - header(key): the value of the data file's `# key = value` line (quotes removed; empty if absent),
#     so that titles and labels follow the options the program was run with, not this script.
#   - scheme_name(id), mass_name(id): the names the data file's `# label` lines give the ids;
#     scheme_title(id): the title its `# title` line gives a row of the scheme.
set encoding utf8
fontface = "Latin Modern Roman"
font(size) = sprintf("%s,%g", fontface, size)
# The one terminal of the report's figures: PDF, text at 10 pt (the size of the captions; the body is
# set at 11), lines 1.5 times cairo's default. A script sets `set terminal @figure_terminal size W,H`
# with W the width at which the report includes the figure, so that the text prints at 10 pt: 16 cm
# for a figure at \textwidth (16.4 cm: A4 with margins of 2.3 cm, a scale of 1.025), and
# fraction * text_width for one at a fraction of it. Every label, key and tic keeps this size; a figure
# with more text than room gets more height or fewer panels a row, not a smaller font.
text_width = 16.4
figure_terminal = sprintf("pdfcairo font '%s' linewidth 1.5 enhanced", font(10))
# The data file's comment lines, read once (one process each, instead of one per lookup: a figure looks
# up hundreds of labels and values, and a process each made gnuplot most of `make all`'s time):
# comment(text, prefix) is the rest of the first line of `text` that starts with `prefix`, or "".
comments = "\n".system(sprintf("grep '^# ' '%s'", data))."\n"
comments_unquoted = "\n".system(sprintf("grep '^# ' '%s' | tr -d '\"'", data))."\n"
comment_rest(text, p, n) = p == 0 ? "" : text[p + 1 + n:]
comment_line(r) = r[1:strstrt(r, "\n") - 1]
comment(text, prefix) = comment_line(comment_rest(text, strstrt(text, "\n".prefix), strlen(prefix)))
# A key may be written as a sed pattern ("dt\\/h"): its backslashes are dropped.
unescape(k) = strstrt(k, "\\") == 0 ? k : k[1:strstrt(k, "\\") - 1].unescape(k[strstrt(k, "\\") + 1:])
header(key) = comment(comments_unquoted, "# ".unescape(key)." = ")
italic(s) = "{/:Italic ".s."}"
# Math italic lambda (U+1D706) from the math font, as the report's $\lambda$.
lambda_ = "{/'Latin Modern Math' 𝜆}"
# Every other lower-case Greek letter (and √) likewise: Latin Modern Roman's text font has none, and cairo
# would fall back to DejaVu Sans for it. math(c) sets any character in the math font; the letters the
# figures use are named. Pass the math italic letters (U+1D6FC…) for variables, as the report's $\beta$.
math(c) = "{/'Latin Modern Math' ".c."}"
beta_ = math("𝛽")
delta_ = math("𝛿")
xi_ = math("𝜉")
omega_ = math("𝜔")
gamma_ = math("𝛾")
epsilon_ = math("𝜀")
Delta_t = "Δ".italic("t")
# A name from the data file with its Greek letters in the math font (the labels write "Newmark (β, γ)").
replace(s, a, b) = strstrt(s, a) == 0 ? s : s[1:strstrt(s, a) - 1].b.replace(s[strstrt(s, a) + strlen(a):], a, b)
greek(s) = replace(replace(s, "β", beta_), "γ", gamma_)
mass_colour(m) = m == 1 ? "#d62728" : m == 2 ? "#1f77b4" : m == 3 ? "#2ca02c" : "#9467bd"
# The colour of curve k where the curves are variants of one run (stresses, steps, blends), neither masses
# nor schemes: one palette for every such figure.
curve_colour(k) = word("#1f77b4 #ff7f0e #2ca02c #d62728 #9467bd #8c564b #e377c2 #17becf", (k - 1) % 8 + 1)
# The line styles every figure shares, as macros (`with linespoints lc rgb c @measured_style`):
#   measured_style  a measured curve: lines 1.2, filled circles;
#   reference_style a reference slope (grey, thin; dashed with dt 3 for the lower order, dt 4 for the
#                   higher one);
#   exact_style     the exact solution (black, thick).
measured_style = "lw 1.2 pt 7 ps 0.5"
reference_style = "lc rgb '#777777' lw 1"
exact_style = "lc rgb 'black' lw 2"
# The names of schemes and masses: the `# label <id> = <name>` lines the program wrote into the data
# file (repro/labels.cpp, the one table of labels); an id without a line is its own name.
label(id) = comment(comments, "# label ".id." = ")
mass_name(id) = label(id) eq "" ? id : greek(label(id))
scheme_name(id) = label(id) eq "" ? id : greek(label(id))
# The title of a figure's row of scheme `id`: the `# title <id> = <title>` line of the data file (its
# name, with the contact row for a scheme that takes one; repro/labels.cpp, write_scheme_titles).
scheme_title(id) = comment(comments, "# title ".id." = ")
# One colour per scheme where the schemes are the curves (the energy-conserving schemes' figures), none
# of them a mass's colour: the data file's `# colour <id> = <colour>` line (grey without one).
scheme_colour(id) = header("colour ".id) eq "" ? "#7f7f7f" : header("colour ".id)
# The eight measures of mathematics.md §5, from their column names in the data files.
measure_name(id) = \
  id eq "err_u0_L2" ? italic("u")."(0,·) in ".italic("L")."^2(0,".italic("T").")" : \
  id eq "err_lambda_L2" ? lambda_." in ".italic("L")."^2(0,".italic("T").")" : \
  id eq "err_u_LinfL2" ? italic("u")." in ".italic("L")."^∞(0,".italic("T").";".italic("L")."^2)" : \
  id eq "err_u_LinfH1" ? italic("u")." in ".italic("L")."^∞(0,".italic("T").";".italic("H")."^1)" : \
  id eq "err_v_LinfL2" ? italic("u")."_{/:Italic t} in ".italic("L")."^∞(0,".italic("T").";".italic("L")."^2)" : \
  id eq "err_u_L2L2" ? italic("u")." in ".italic("L")."^2(0,".italic("T").";".italic("L")."^2)" : \
  id eq "err_u_L2H1" ? italic("u")." in ".italic("L")."^2(0,".italic("T").";".italic("H")."^1)" : \
  id eq "err_v_L2L2" ? italic("u")."_{/:Italic t} in ".italic("L")."^2(0,".italic("T").";".italic("L")."^2)" : id
# The same, short, for tic labels.
measure_short(id) = \
  id eq "err_u0_L2" ? italic("u")."(0,·), ".italic("L")."^2_{/:Italic t}" : \
  id eq "err_lambda_L2" ? lambda_.", ".italic("L")."^2_{/:Italic t}" : \
  id eq "err_u_LinfL2" ? italic("u").", ".italic("L")."^∞_{/:Italic t}".italic("L")."^2" : \
  id eq "err_u_LinfH1" ? italic("u").", ".italic("L")."^∞_{/:Italic t}".italic("H")."^1" : \
  id eq "err_v_LinfL2" ? italic("u")."_{/:Italic t}, ".italic("L")."^∞_{/:Italic t}".italic("L")."^2" : \
  id eq "err_u_L2L2" ? italic("u").", ".italic("L")."^2_{/:Italic t}".italic("L")."^2" : \
  id eq "err_u_L2H1" ? italic("u").", ".italic("L")."^2_{/:Italic t}".italic("H")."^1" : \
  id eq "err_v_L2L2" ? italic("u")."_{/:Italic t}, ".italic("L")."^2_{/:Italic t}".italic("L")."^2" : id
# The column names of a `# columns: ...` line (the first one of the file).
columns = system(sprintf("sed -n 's/^# columns: //p' '%s' | head -n 1", data))
set grid lc rgb "#dddddd" lw 0.5
# A log axis fitted to the data: after `stats` of the plotted values (positive ones; `set autoscale y`
# before it, or stats skips the values outside the previous panel's range), @fit_log_y sets the y range to the decades that enclose them, so that a reference slope is clipped to the data's range
# instead of stretching the axis to where no datum is.
fit_log_y = "set yrange [10**floor(log10(STATS_min) + 1e-9):10**ceil(log10(STATS_max) - 1e-9)]"
positive(v) = v > 0 ? v : NaN
# The energies' symbols, as in the report: the two-level E_h and Paoli–Schatzman's E_h^β.
E_h = "{/:Italic E}_{/:Italic h}"
E_h_beta = "{/:Italic E}_{/:Italic h}^".beta_
# Small multiples placed by hand (a `layout` would also give the key its own plot): set grid_cols,
# grid_rows and the grid's edges and gaps (screen fractions; the gaps hold a title, the edges the tic
# labels and axis labels of the outer panels), then `@grid_setup` once and, for panel k (0 the top left,
# row by row), `@grid_panel` before its plot. grid_left_column(k) and grid_bottom_row(k, n) (n panels in
# all: no panel below k) say where a panel needs its tic labels and axis labels.
grid_left = 0.1; grid_right = 0.98; grid_bottom = 0.07; grid_top = 0.95; grid_gap_x = 0.02; grid_gap_y = 0.05
grid_setup = "grid_w = (grid_right - grid_left - (grid_cols - 1) * grid_gap_x) / grid_cols; grid_h = (grid_top - grid_bottom - (grid_rows - 1) * grid_gap_y) / grid_rows"
grid_x(k) = grid_left + (k % grid_cols) * (grid_w + grid_gap_x)
grid_y(k) = grid_top - (k / grid_cols) * (grid_h + grid_gap_y)
grid_panel = "set lmargin at screen grid_x(k); set rmargin at screen grid_x(k) + grid_w; set tmargin at screen grid_y(k); set bmargin at screen grid_y(k) - grid_h"
grid_left_column(k) = k % grid_cols == 0
grid_bottom_row(k, n) = k + grid_cols >= n
