# The pointing study's report computed independently in base R from a tidy
# CSV (apps/study tidy.hpp; docs/studies.md, "Analysis: the pointing study's
# report"): the reference the C++ report (pointing_report.hpp) is checked
# against, key for key.
#
# Usage: Rscript pointing_reference.R tidy.csv report.json [level,level,…]
#   level order: the renderings in order, the control first; without it,
#   the order in which the analysed rows first name them.
# Writes the report's JSON keys (to_json's, without "notes") to report.json.
# Base R only (no jsonlite in the sysroot): the JSON is written by hand,
# numbers as %.17g.
args <- commandArgs(trailingOnly = TRUE)
if (length(args) < 2) stop("usage: Rscript pointing_reference.R tidy.csv report.json [level,level,...]")
# Codes and names as text, even where they look like numbers ("01").
all_rows <- read.csv(args[1], stringsAsFactors = FALSE,
                     colClasses = c(participant = "character", stage = "character", rendering = "character"))
columns <- c("participant", "session", "block", "trial", "practice", "stage", "rendering", "amplitude_deg",
             "width_deg", "acquisition", "direction", "movement_time_s", "endpoint_deg", "overshoot_deg",
             "rating", "emg_uV", "sc_uS")
missing <- setdiff(columns, names(all_rows))
if (length(missing) > 0) stop("missing columns: ", paste(missing, collapse = ", "))
d <- all_rows[all_rows$practice == 0, ]
levels <- if (length(args) >= 3) strsplit(args[3], ",")[[1]] else unique(d$rendering)
k <- length(levels)
participants <- unique(d$participant)
d$key <- paste(d$participant, d$session, d$block, d$trial, sep = "\r")

# One row per trial: its rendering, rating, mean movement time, mean EMG and
# SC over the rows that have them (NA when none).
trial_keys <- unique(d$key)
first <- d[match(trial_keys, d$key), ]
mean_or_na <- function(v) if (all(is.na(v))) NA_real_ else mean(v, na.rm = TRUE)
trials <- data.frame(
  key = trial_keys, participant = first$participant, rendering = first$rendering, rating = first$rating,
  mt = as.numeric(tapply(d$movement_time_s, d$key, mean)[trial_keys]),
  emg = as.numeric(tapply(d$emg_uV, d$key, mean_or_na)[trial_keys]),
  sc = as.numeric(tapply(d$sc_uS, d$key, mean_or_na)[trial_keys]),
  stringsAsFactors = FALSE)

# Participants with every rendering: the ANOVA's and the rating tests' cases.
complete <- participants[sapply(participants, function(p) all(levels %in% d$rendering[d$participant == p]))]
n <- length(complete)
participant_mt <- t(sapply(complete, function(p) sapply(levels, function(g)
  mean(d$movement_time_s[d$participant == p & d$rendering == g]))))
participant_rating <- t(sapply(complete, function(p) sapply(levels, function(g)
  mean(trials$rating[trials$participant == p & trials$rendering == g]))))
participant_median <- t(sapply(complete, function(p) sapply(levels, function(g)
  median(trials$rating[trials$participant == p & trials$rendering == g]))))

# t.test refuses constant data; their interval is the point itself.
interval <- function(v) {
  ci <- if (sd(v) == 0) c(mean(v), mean(v)) else t.test(v)$conf.int
  list(mean = mean(v), low = ci[1], high = ci[2], participants = length(v))
}

renderings <- list()
for (j in seq_len(k)) {
  g <- levels[j]
  x <- d[d$rendering == g, ]
  aw <- unique(x[, c("amplitude_deg", "width_deg")])
  aw <- aw[order(aw$amplitude_deg, aw$width_deg), ]
  cells <- list()
  for (c in seq_len(nrow(aw))) {
    A <- aw$amplitude_deg[c]
    W <- aw$width_deg[c]
    sel <- x$amplitude_deg == A & x$width_deg == W
    e <- x$endpoint_deg[sel]
    mt <- x$movement_time_s[sel]
    We <- 4.133 * sd(e)
    IDe <- log2(A / We + 1)
    cells[[c]] <- list(amplitude_deg = A, width_deg = W, n = length(e), We_deg = We, IDe_bits = IDe,
                       throughput_bits_per_s = IDe / mean(mt), movement_time_s = mean(mt),
                       welford_id = log10(A / W + 0.5), endpoint_mean_deg = mean(e), endpoint_sd_deg = sd(e))
  }
  cell_value <- function(name) sapply(cells, function(c) c[[name]])
  r <- list(rendering = g, We_deg = mean(cell_value("We_deg")), IDe_bits = mean(cell_value("IDe_bits")),
            throughput_bits_per_s = mean(cell_value("throughput_bits_per_s")),
            movement_time_s = mean(x$movement_time_s),
            rating_mean = mean(trials$rating[trials$rendering == g]),
            trials = sum(trials$rendering == g), acquisitions = nrow(x),
            movement_time_by_participant = interval(participant_mt[, j]),
            rating_by_participant = interval(participant_rating[, j]),
            cells = cells)
  ide <- cell_value("IDe_bits")
  cmt <- cell_value("movement_time_s")
  if (length(unique(ide)) >= 2 && length(unique(cmt)) >= 2) {
    fit <- lm(cmt ~ ide)
    r$fitts_line <- list(intercept_s = unname(coef(fit)[1]), slope_s_per_bit = unname(coef(fit)[2]),
                         r_squared = summary(fit)$r.squared)
  }
  renderings[[j]] <- r
}

# Repeated-measures ANOVA of the participants' mean movement times, as
# tests/stats/rm_anova_reference.R: anova.mlm's sphericity test for F, p
# and the corrected p, stats:::sphericity for the epsilons whole, aov's
# strata for the sums of squares (partial η²).
Y <- unname(participant_mt)
fit <- lm(Y ~ 1)
a <- anova(fit, X = ~1, test = "Spherical")
sph <- stats:::sphericity(SSD(fit), X = ~1)
long <- data.frame(y = as.vector(Y), subject = factor(rep(seq_len(n), k)), condition = factor(rep(seq_len(k), each = n)))
within <- summary(aov(y ~ condition + Error(subject / condition), data = long))[["Error: subject:condition"]][[1]]
rownames(within) <- trimws(rownames(within))
anova_mt <- list(F = a[1, "F"], df1 = a[1, "num Df"], df2 = a[1, "den Df"], p = a[1, "Pr(>F)"],
                 p_gg = a[1, "G-G Pr"], epsilon_gg = sph$GG.eps, p_hf = a[1, "H-F Pr"], epsilon_hf = sph$HF.eps,
                 partial_eta_squared = within["condition", "Sum Sq"] /
                   (within["condition", "Sum Sq"] + within["Residuals", "Sum Sq"]),
                 participants = n)

out <- list(renderings = renderings, anova_movement_time = anova_mt)

M <- unname(participant_median)
if (k >= 3) {
  f <- friedman.test(M)
  if (is.finite(f$statistic))
    out$friedman_rating <- list(chi_squared = unname(f$statistic), df = unname(f$parameter), p = f$p.value,
                                participants = n)
}

# Wilcoxon signed-rank of each rendering's medians against the control's, by
# apps/stats' convention (scipy's): zero differences dropped; exact for ≤ 50
# pairs without ties or zeros (R's own exact test), for ≤ 13 pairs with ties
# or zeros the sign-flip distribution of the tied ranks (enumerated here:
# R's exact test refuses ties), otherwise the normal approximation without
# continuity correction (R's, correct = FALSE).
wilcoxon <- list()
p_values <- c()
for (j in seq_len(k)[-1]) {
  x <- M[, j]
  y <- M[, 1]
  dd <- x - y
  nz <- dd[dd != 0]
  w <- list(rendering = levels[j], control = levels[1])
  if (length(nz) == 0) {
    w$zeros <- length(dd)
    wilcoxon[[length(wilcoxon) + 1]] <- w
    next
  }
  m <- length(nz)
  rk <- rank(abs(nz))
  r_plus <- sum(rk[nz > 0])
  r_minus <- sum(rk[nz < 0])
  ties <- anyDuplicated(abs(nz)) > 0
  zeros <- sum(dd == 0)
  pairs <- length(dd)
  exact <- pairs <= 50 && ((!ties && zeros == 0) || pairs <= 13)
  tie_sizes <- table(abs(nz))
  z <- (r_plus - m * (m + 1) / 4) / sqrt(m * (m + 1) * (2 * m + 1) / 24 - sum(tie_sizes^3 - tie_sizes) / 48)
  if (exact && !ties && zeros == 0) {
    test <- wilcox.test(x, y, paired = TRUE, exact = TRUE)
    stopifnot(unname(test$statistic) == r_plus)
    p <- test$p.value
  } else if (exact) {
    signs <- as.matrix(expand.grid(rep(list(c(0, 1)), m)))
    sums <- as.vector(signs %*% rk)
    p <- min(1, 2 * min(mean(sums <= r_plus + 1e-9), mean(sums >= r_plus - 1e-9)))
  } else {
    test <- suppressWarnings(wilcox.test(x, y, paired = TRUE, exact = FALSE, correct = FALSE))
    stopifnot(unname(test$statistic) == r_plus)
    p <- test$p.value
  }
  w$W <- min(r_plus, r_minus)
  w$r_plus <- r_plus
  w$z <- z
  w$p <- p
  w$n <- m
  w$zeros <- zeros
  w$method <- if (exact) "exact" else "normal"
  p_values[length(wilcoxon) + 1] <- p
  wilcoxon[[length(wilcoxon) + 1]] <- w
}
adjusted <- p.adjust(p_values, method = "bonferroni", n = k - 1)
for (i in seq_along(wilcoxon)) if (!is.null(wilcoxon[[i]]$p)) wilcoxon[[i]]$p_bonferroni <- adjusted[i]
out$wilcoxon_rating <- wilcoxon

# Spearman over trials, with the t approximation apps/stats uses (scipy's
# spearmanr; R's cor.test with exact = FALSE).
spearman <- function(a, b) {
  if (length(a) < 3 || sd(a) == 0 || sd(b) == 0) return(NULL)
  test <- suppressWarnings(cor.test(a, b, method = "spearman", exact = FALSE))
  list(rho = unname(test$estimate), p = test$p.value, n = length(a))
}
correlations <- setNames(list(), character(0))
correlations$movement_time_rating <- spearman(trials$mt, trials$rating)
with_emg <- !is.na(trials$emg)
if (any(with_emg)) correlations$rating_emg <- spearman(trials$rating[with_emg], trials$emg[with_emg])
with_sc <- !is.na(trials$sc)
if (any(with_sc)) correlations$rating_sc <- spearman(trials$rating[with_sc], trials$sc[with_sc])
out$correlations <- correlations
out$participants <- as.list(complete)
out$trials <- nrow(trials)
out$acquisitions <- nrow(d)

# JSON by hand: named lists are objects, unnamed lists arrays.
json <- function(v) {
  if (is.list(v)) {
    if (length(v) == 0) return(if (is.null(names(v))) "[]" else "{}")
    if (is.null(names(v))) return(paste0("[", paste(sapply(v, json), collapse = ","), "]"))
    return(paste0("{", paste(sprintf("\"%s\":%s", names(v), sapply(v, json)), collapse = ","), "}"))
  }
  if (is.character(v)) return(paste0("\"", gsub("\"", "\\\\\"", gsub("\\\\", "\\\\\\\\", v)), "\""))
  if (is.na(v) || !is.finite(v)) return("null")
  sprintf("%.17g", v)
}
writeLines(json(out), args[2])
