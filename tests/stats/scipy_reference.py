"""scipy.stats on a CSV the apps/stats tests wrote: the reference values they
compare against. Usage: scipy_reference.py CHECK data.csv; prints "name value"
lines (repr, so every digit survives)."""
import sys

import numpy as np
from scipy import special, stats


def distributions(rows):
    # Each row: code, x, a, b. The codes are distributions_test.cpp's.
    for i, (code, x, a, b) in enumerate(rows):
        code = int(code)
        if code == 0:
            d = stats.norm()
        elif code == 1:
            d = stats.t(a)
            yield f"two_sided.{i}", 2 * d.sf(abs(x))
        elif code == 2:
            d = stats.chi2(a)
        elif code == 3:
            d = stats.f(a, b)
        if code <= 3:
            yield f"sf.{i}", d.sf(x)
            yield f"cdf.{i}", d.cdf(x)
        elif code == 4:
            yield f"cdf.{i}", special.betainc(a, b, x)
        elif code == 5:
            yield f"cdf.{i}", special.gammainc(a, x)
            yield f"sf.{i}", special.gammaincc(a, x)


def friedman(rows):
    res = stats.friedmanchisquare(*rows.T)
    yield "statistic", res.statistic
    yield "p", res.pvalue


def wilcoxon(rows):
    x, y = rows.T
    auto = stats.wilcoxon(x, y)  # scipy's defaults: zero_method="wilcox", correction=False, method="auto"
    yield "statistic", auto.statistic
    yield "p", auto.pvalue
    for name, correction in (("normal", False), ("normal_cc", True)):
        res = stats.wilcoxon(x, y, method="asymptotic", correction=correction)
        yield f"p_{name}", res.pvalue
        yield f"abs_z_{name}", abs(res.zstatistic)


def correlation(function):
    def check(rows):
        res = function(*rows.T)
        yield "r", res.statistic
        yield "p", res.pvalue
    return check


def ttest_rel(rows):
    res = stats.ttest_rel(*rows.T)
    yield "t", res.statistic
    yield "p", res.pvalue


def linregress(rows):
    res = stats.linregress(*rows.T)
    yield "slope", res.slope
    yield "intercept", res.intercept
    yield "r_squared", res.rvalue ** 2


def effective_throughput(rows):
    # Each row: end-point, movement time, amplitude (the same in every row).
    endpoints, times, amplitude = rows[:, 0], rows[:, 1], rows[0, 2]
    sd = np.std(endpoints, ddof=1)
    width = 4.133 * sd
    ide = np.log2(amplitude / width + 1)
    yield "variance", np.var(endpoints, ddof=1)
    yield "effective_width", width
    yield "index_of_difficulty", ide
    yield "throughput", ide / np.mean(times)


CHECKS = {
    "distributions": distributions,
    "friedman": friedman,
    "wilcoxon": wilcoxon,
    "pearson": correlation(stats.pearsonr),
    "spearman": correlation(stats.spearmanr),
    "ttest_rel": ttest_rel,
    "linregress": linregress,
    "effective_throughput": effective_throughput,
}

if __name__ == "__main__":
    check, path = sys.argv[1], sys.argv[2]
    rows = np.loadtxt(path, delimiter=",", ndmin=2)
    for name, value in CHECKS[check](rows):
        print(name, repr(float(value)))
