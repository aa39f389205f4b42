"""Seed 004 Table 3.5, what makes the ellipse's rear amplitude differ: the Reynolds parameter lambda_bar (eq 2.15)
against the contact geometry, the indent position, and where on the shoulder ring the amplitude sits.

    flock /tmp/femcheck-cpu.lock python benchmarks/ehl_ellipticity_causes.py CASE [CASE ...]

CASE = GRID:M:L:Phi:D/Phi:kappa:LAM:y_half:TAG[:N], the contact of benchmarks/ehl_ellipticity.py ((M, L) the
circle's Moes point, kappa at constant b and p_H, the same physical indent, K = 4, Roelands and Dowson-Higginson).
LAM: ``none`` (the thesis' comparison: lambda_bar = 12 u_m eta0 Rx^2/(b^3 p_H) follows Rx, x 0.657 at kappa 0.2),
``circle`` (the ellipse run at the circle's lambda_bar: u_m x (Rx(1)/Rx)^2, so only the geometry differs) or
``ellipse`` (the circle at the kappa = 0.2 ellipse's lambda_bar). The indent is marched from the inlet to
X_D = N/4 b (default 2), the amplitudes (femcheck.ehl.outputs.additional_pressure) read at X_D = -0.5, -0.25, 0,
... b; at X_D = 0 also the rear maximum's position and the maximum of dP on the centre line upstream. One JSON
line per case to benchmarks/results/ehl_ellipticity_causes.jsonl; the fields at X_D = 0 to /tmp/TAG.npz."""
import dataclasses, json, sys, time
import numpy as np
sys.path.insert(0, "benchmarks")
import ehl_ellipticity as EE
from femcheck.ehl import groups, model, outputs, transient
from femcheck.ehl.film import Indent

def run(grid, M, L, phi, slope, kappa, lam_to, y_half, tag, nmax=2):
    g1 = groups.from_moes(M, L, EE.RX, EE.RX, EE.E_PRIME, EE.ETA0, EE.ALPHA)
    g = groups.at_ellipticity(g1, kappa)
    if lam_to == "circle":      # the ellipse with the circle's lambda_bar (u_mean x (Rx1/Rx)^2)
        g = groups.from_physical(g.Rx, g.Ry, g.e_prime, g.load, g.eta0, g.alpha, g.u_mean * (g1.Rx / g.Rx) ** 2)
    elif lam_to == "ellipse":   # the circle with the kappa=0.2 ellipse's lambda_bar
        ge = groups.at_ellipticity(g1, 0.2)
        g = groups.from_physical(g.Rx, g.Ry, g.e_prime, g.load, g.eta0, g.alpha, g.u_mean * (ge.Rx / g1.Rx) ** 2)
    sl = slope * g.Rx / g1.Rx
    t = time.perf_counter()
    s = model.make_setup(g, "roelands", "dowson_higginson", grid, None, -2.5, 1.5, y_half=y_half)
    smooth, mg = model.solve_smooth(s, 1e-7, 1e-7)
    h = mg.fine.h
    centre, _ = model.crossing_steps(phi, -2.5, h, 1.0)
    ind = Indent(phi, sl * phi, 4.0, x0=-centre * h, speed_ratio=1.0)
    mg.prob = dataclasses.replace(s.prob, indent=ind)
    mg.set_time(0.0); transient.start(mg)
    n8 = (grid - 1) // 16          # 0.25 b
    offs = [o * n8 for o in range(-2, nmax + 1)]
    want = {centre + o for o in offs}
    hist = transient.march(mg, centre + nmax * n8, tol=1e-7, load_tol=1e-7, keep=lambda k, T: k in want, base=smooth.P)
    pos = {}
    for o, sn in zip(offs, hist.snapshots):
        xd = o * h
        aa = outputs.additional_pressure(sn.x, sn.y, sn.P - smooth.P, xd, 0.0, phi)
        pos[f"{xd:+.3f}"] = {k: aa[k] for k in ("rear", "front", "lateral", "centre")}
    sol = hist.snapshots[2]
    dP = sol.P - smooth.P
    a = outputs.additional_pressure(sol.x, sol.y, dP, 0.0, 0.0, phi)
    j0 = int(np.argmin(abs(sol.y)))
    X, Y = np.meshgrid(sol.x, sol.y, indexing="ij")
    rz = (X < 0) & (-X > abs(Y)) & (np.hypot(X, Y) < 1.5 * phi) & (np.hypot(X, Y) > 0.5 * phi)
    i = np.unravel_index(np.argmax(np.where(rz, dP, -np.inf)), dP.shape)
    line = dP[:, j0]
    up = sol.x < 0
    r = {"tag": tag, "grid": grid, "M": M, "L": L, "phi": phi, "slope": slope, "kappa": kappa, "lam_to": lam_to,
         "lam": s.prob.lam if hasattr(s.prob, "lam") else None, "slope_used": sl,
         **{k: a[k] for k in ("rear", "front", "lateral", "centre")},
         "rear_at": [float(X[i]), float(Y[i])], "line_rear": float(line[up].max()),
         "line_rear_at": float(sol.x[up][np.argmax(line[up])]),
         "H0": float(getattr(sol, "H0", np.nan)) if hasattr(sol, "H0") else None,
         "hmin": float(min(hist.h_min)), "positions": pos, "time_s": time.perf_counter() - t}
    np.savez(f"/tmp/{tag}.npz", x=sol.x, y=sol.y, dP=dP, Ps=smooth.P, P=sol.P, H=getattr(sol, "H", np.zeros(1)), Hs=getattr(smooth, "H", np.zeros(1)))
    print(json.dumps(r), flush=True)
    with open("benchmarks/results/ehl_ellipticity_causes.jsonl", "a") as f:
        f.write(json.dumps(r) + "\n")

if __name__ == "__main__":
    for case in sys.argv[1:]:
        grid, M, L, phi, slope, kappa, lam_to, yh, tag, *nm = case.split(":")
        try:
            run(int(grid), float(M), float(L), float(phi), float(slope), float(kappa), lam_to, float(yh), tag,
                int(nm[0]) if nm else 2)
        except Exception as err:
            print(tag, "FAILED", str(err)[:300], flush=True)
