# Base R's repeated-measures ANOVA on a CSV the apps/stats tests wrote (rows:
# subjects, columns: conditions): the reference values they compare against.
# Usage: Rscript rm_anova_reference.R data.csv; prints "name value" lines.
args <- commandArgs(trailingOnly = TRUE)
Y <- as.matrix(read.csv(args[1], header = FALSE))

# The multivariate route: the within-subject effect is the intercept model's
# test on contrasts orthogonal to ~1, with the sphericity corrections.
fit <- lm(Y ~ 1)
a <- anova(fit, X = ~1, test = "Spherical")
# anova.mlm prints the epsilons to 4 digits only; the function it gets them
# from (internal to stats) gives them whole.
sph <- stats:::sphericity(SSD(fit), X = ~1)

# The univariate route, for the sums of squares: aov with a subject stratum.
long <- data.frame(y = as.vector(Y),
                   subject = factor(rep(seq_len(nrow(Y)), ncol(Y))),
                   condition = factor(rep(seq_len(ncol(Y)), each = nrow(Y))))
strata <- summary(aov(y ~ condition + Error(subject / condition), data = long))
within <- strata[["Error: subject:condition"]][[1]]
between <- strata[["Error: subject"]][[1]]
# summary.aov pads its row names.
rownames(within) <- trimws(rownames(within))
rownames(between) <- trimws(rownames(between))

out <- c(f = a[1, "F"], df1 = a[1, "num Df"], df2 = a[1, "den Df"], p = a[1, "Pr(>F)"],
         epsilon_gg = sph$GG.eps, p_gg = a[1, "G-G Pr"],
         epsilon_hf = sph$HF.eps, p_hf = a[1, "H-F Pr"],
         ss_conditions = within["condition", "Sum Sq"],
         ss_error = within["Residuals", "Sum Sq"],
         ss_subjects = between["Residuals", "Sum Sq"],
         aov_f = within["condition", "F value"])
for (name in names(out)) cat(name, format(out[[name]], digits = 17), "\n")
