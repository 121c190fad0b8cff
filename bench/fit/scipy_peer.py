#!/usr/bin/env python3
"""The scipy peer of knoblab-fit-bench: the thesis' Eq. 6 knob model fitted
with scipy.optimize.least_squares to the CSV the benchmark writes.

    python3 scipy_peer.py data.csv [--repeats N]

data.csv has a header and the columns t, theta, omega, alpha, torque (SI).
The model and parameter order are knoblab's (model::ThesisParam):

    tau = M*alpha + [w>0]*(C_pos + B_pos*w) + [w<0]*(-C_neg + B_neg*w)
          + A*sin(theta/P + S)
    p   = (M_acc, C_vel_neg, B_vel_neg, C_vel_pos, B_vel_pos, A_pos, P_pos, S_pos)

Fairness. knoblab starts from nothing: it finds the detent period by itself.
Eq. 6 is not convex in P (every neighbouring detent count is a local
minimum), so least_squares needs a start near the answer; we give it the most
favourable one there is, the TRUE parameters the data were made with
(--start overrides). Its timings are therefore a lower bound on what a scipy
user would pay. Only the least_squares call is timed: not reading the CSV,
not building the model, not importing scipy.

Variants, each timed --repeats times (at least 3), the median reported:
  trf-2point     method='trf', jac='2-point'  (what a user writes by default)
  lm-2point      method='lm',  jac='2-point'  (MINPACK, forward differences)
  lm-analytic    method='lm',  analytic Jacobian (vectorised numpy)
Tolerances are knoblab's Ceres ones: ftol = xtol = 1e-12, gtol = 1e-14
(function, parameter and gradient tolerance). MINPACK accepts them (they
are above machine epsilon), and trf meets them within its default max_nfev
from the true start; a variant that fails is reported with "ok": false.

Output: one JSON line on stdout,
  {"variants": [{"name", "seconds", "runs", "cpu_seconds", "params", "rmse", "nfev",
                 "njev", "status", "ok"}, ...],
   "best": name of the fastest variant that succeeded, ...}
seconds is the median wall time, cpu_seconds the median process CPU time
(all threads; less sensitive to a loaded machine). rmse is
sqrt(mean(residual^2)) over every sample.
"""

import argparse
import json
import statistics
import sys
import time

import numpy as np
import scipy
from scipy.optimize import least_squares

TRUTH = [0.4, 1.5, 1.0, 2.0, 1.5, 1.0, 0.2, 0.9]  # thesis Eq. 10
NAMES = ["M_acc", "C_vel_neg", "B_vel_neg", "C_vel_pos", "B_vel_pos",
         "A_pos", "P_pos", "S_pos"]
TOL = dict(ftol=1e-12, xtol=1e-12, gtol=1e-14)


class Eq6:
    """Residuals model(p) - torque and their Jacobian, vectorised."""

    def __init__(self, theta, omega, alpha, torque):
        self.theta = theta
        self.alpha = alpha
        self.torque = torque
        self.omega = omega
        neg = omega < 0
        pos = omega > 0
        # The friction columns do not depend on p: precompute them.
        self.neg = neg.astype(float)
        self.pos = pos.astype(float)
        self.w_neg = np.where(neg, omega, 0.0)
        self.w_pos = np.where(pos, omega, 0.0)

    def residuals(self, p):
        M, Cn, Bn, Cp, Bp, A, P, S = p
        return (M * self.alpha
                + self.pos * Cp + self.w_pos * Bp
                - self.neg * Cn + self.w_neg * Bn
                + A * np.sin(self.theta / P + S)
                - self.torque)

    def jacobian(self, p):
        _, _, _, _, _, A, P, S = p
        phi = self.theta / P + S
        s = np.sin(phi)
        c = np.cos(phi)
        J = np.empty((self.theta.size, 8))
        J[:, 0] = self.alpha
        J[:, 1] = -self.neg
        J[:, 2] = self.w_neg
        J[:, 3] = self.pos
        J[:, 4] = self.w_pos
        J[:, 5] = s
        J[:, 6] = -A * c * self.theta / (P * P)
        J[:, 7] = A * c
        return J


def run_variant(name, model, x0, repeats, **kwargs):
    runs, cpu = [], []
    res = None
    for _ in range(repeats):
        c0 = time.process_time()
        t0 = time.perf_counter()
        res = least_squares(model.residuals, x0, **kwargs, **TOL)
        runs.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    r = model.residuals(res.x)
    return {
        "name": name,
        "seconds": statistics.median(runs),
        "runs": runs,
        "cpu_seconds": statistics.median(cpu),
        "params": [float(v) for v in res.x],
        "rmse": float(np.sqrt(np.mean(r * r))),
        "nfev": int(res.nfev),
        "njev": int(res.njev) if res.njev is not None else None,
        "status": int(res.status),
        "message": str(res.message),
        "ok": bool(res.success),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv")
    ap.add_argument("--repeats", type=int, default=3,
                    help="timed runs per variant (at least 3; default 3)")
    ap.add_argument("--start", type=float, nargs=8, default=TRUTH,
                    help="start vector (default: the true parameters)")
    args = ap.parse_args()
    repeats = max(3, args.repeats)

    data = np.loadtxt(args.csv, delimiter=",", skiprows=1, ndmin=2)
    if data.shape[1] < 5 or data.shape[0] < 16:
        sys.exit("scipy_peer: expected columns t,theta,omega,alpha,torque")
    model = Eq6(*(np.ascontiguousarray(data[:, k]) for k in range(1, 5)))
    x0 = np.asarray(args.start, dtype=float)

    variants = [
        run_variant("trf-2point", model, x0, repeats, method="trf", jac="2-point"),
        run_variant("lm-2point", model, x0, repeats, method="lm", jac="2-point"),
        run_variant("lm-analytic", model, x0, repeats, method="lm", jac=model.jacobian),
    ]
    ok = [v for v in variants if v["ok"]]
    best = min(ok, key=lambda v: v["seconds"])["name"] if ok else None
    print(json.dumps({
        "variants": variants,
        "best": best,
        "names": NAMES,
        "start": [float(v) for v in x0],
        "start_is_truth": list(x0) == TRUTH,
        "samples": int(data.shape[0]),
        "repeats": repeats,
        "tolerances": TOL,
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "python": sys.version.split()[0],
    }))
    return 0 if best is not None else 1


if __name__ == "__main__":
    sys.exit(main())
