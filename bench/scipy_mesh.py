"""The marine-reducer mesh equations in Python for scipy.integrate.solve_ivp: the same
parameters (written by `dynamics_bench params`), the same sample times and output
(rms of the acceleration over the recorded mesh period), the same scaled tolerances.
Prints "method rtol error cpu_s rhs" lines, error against gbxc's reference at rtol 1e-14."""
import json, math, sys, time
import numpy as np
from scipy.integrate import solve_ivp

p = json.load(open(sys.argv[1]))
a, b = p["a"], p["b"]
two_pi = 2 * math.pi

def rel_stiffness(tau):
    w = two_pi * tau
    s = 1.0
    for k in range(len(a)):
        s += a[k] * math.cos((k + 1) * w) + b[k] * math.sin((k + 1) * w)
    return s

calls = [0]
def rhs(t, y):
    calls[0] += 1
    tau = p["z"] * p["omega"] * t / two_pi
    rel = rel_stiffness(tau)
    k = p["k"] * rel
    dk = p["k"] * (rel - 1.0)
    e = p["te_mean"] + p["te_amp"] * math.sin(two_pi * tau + p["te_phase"])
    force = p["F0"] + dk * e - k * y[0] - p["c"] * y[1]
    return [y[1], force / p["m"]]

first, dt, n = p["samples"]
times = first + dt * np.arange(int(n))
scale = np.array(p["scale"])
for method, rtols in (("RK45", [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9]), ("DOP853", [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11])):
    for rtol in rtols:
        calls[0] = 0
        t0 = time.process_time()
        sol = solve_ivp(rhs, (0.0, p["t_end"]), [p["x0"], 0.0], method=method, t_eval=times, rtol=rtol, atol=rtol * scale,
                        max_step=p["max_step"])
        acc = [rhs(t, sol.y[:, i])[1] for i, t in enumerate(sol.t)]
        cpu = time.process_time() - t0
        rms = math.sqrt(sum(x * x for x in acc) / len(acc))
        print(f"{method} {rtol:.0e} {abs(rms - p['reference']) / p['reference']:.6e} {cpu:.6e} {calls[0]}", flush=True)
