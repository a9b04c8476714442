"""Hashes of a handful of op.plan results (grid + circle world, 7 algorithms, with and without
refine): run before and after a change that must not move any number, and diff the output.

    python benchmarks/program_plan_hashes.py OUT.json
"""
import hashlib, json, sys
import numpy as np
import optplan as op
from optplan.solvers.budget import Budget
from optplan.world.papermaps import paper_map

def h(res):
    d = res.to_dict()
    d.pop("runtime_s", None)
    for st in d.get("stages", []) or []:
        pass
    keep = {k: d[k] for k in ("path", "length", "turn_angle_deg", "n_turns", "min_clearance", "feasible", "refined", "nfev") if k in d}
    keep["history"] = np.round(np.asarray(res.history, float), 12).tolist()
    keep["stages"] = [{k: v for k, v in s.items()} for s in (getattr(res, "stages", None) or [])]
    s = json.dumps(keep, sort_keys=True, default=float)
    return hashlib.sha1(s.encode()).hexdigest()[:12], keep

cases = []
gw, gs, gg = paper_map("chen2025_20")
hw, hs, hg = paper_map("hou2024_env1")
cw = op.CircleWorld(bounds=(0, 0, 10, 10), circles=[(3, 3, 1.0), (6, 6, 1.2), (7, 2.5, 0.8)], safety=0.1)
cases = [
  ("grid msiar-gwo", gw, gs, gg, dict(encoding="paper", algorithm="msiar-gwo", pop=20, iters=40)),
  ("grid missa", hw, hs, hg, dict(encoding="paper", algorithm="missa", pop=20, iters=40)),
  ("grid iga", hw, hs, hg, dict(encoding="paper", algorithm="iga", pop=20, iters=40)),
  ("grid iba refine qp", gw, gs, gg, dict(encoding="paper", algorithm="iba", pop=20, iters=40, refine="qp")),
  ("grid missa refine casadi", hw, hs, hg, dict(encoding="paper", algorithm="missa", pop=20, iters=40, refine="casadi")),
  ("grid iga refine casadi", hw, hs, hg, dict(encoding="paper", algorithm="iga", pop=20, iters=40, refine="casadi")),
  ("grid gwo clearance", gw, gs, gg, dict(encoding="paper", algorithm="gwo", pop=20, iters=40, clearance=0.2)),
  ("circle pso", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="pso", pop=20, iters=40)),
  ("circle ipso refine casadi", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="ipso", pop=20, iters=40, refine="casadi")),
  ("circle gwo refine qp", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="gwo", pop=20, iters=40, refine="qp")),
  ("grid astar refine casadi", gw, gs, gg, dict(algorithm="astar", refine="casadi")),
  # the routes issue 24's second part moves onto programs (penalty, pruned, other encodings)
  ("grid missa penalty", hw, hs, hg, dict(encoding="paper", algorithm="missa", pop=20, iters=40, constraint="penalty")),
  ("grid msiar-gwo penalty", gw, gs, gg, dict(encoding="paper", algorithm="msiar-gwo", pop=20, iters=40, constraint="penalty")),
  ("grid gwo penalty clearance", gw, gs, gg, dict(encoding="paper", algorithm="gwo", pop=20, iters=40, constraint="penalty",
                                                  clearance=0.2)),
  ("circle pso penalty", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="pso", pop=20, iters=40, constraint="penalty")),
  ("circle pso penalty small", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="pso", pop=6, iters=30,
                                                                constraint="penalty")),
  ("grid gwo waypoints penalty", gw, gs, gg, dict(algorithm="gwo", pop=8, iters=30, encoding="waypoints",
                                                  constraint="penalty")),
  ("circle gwo general penalty", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="gwo", pop=8, iters=30,
                                                                  encoding="general", constraint="penalty")),
  ("grid msiar-gwo pruned", gw, gs, gg, dict(encoding="paper", algorithm="msiar-gwo", pop=20, iters=40, fitness_on="pruned")),
  ("grid missa pruned penalty", hw, hs, hg, dict(encoding="paper", algorithm="missa", pop=20, iters=40, fitness_on="pruned",
                                                 constraint="penalty")),
  ("grid gwo waypoints", gw, gs, gg, dict(algorithm="gwo", pop=20, iters=40, encoding="waypoints")),
  ("circle pso waypoints", cw, (0.5, 0.5), (9.5, 9.5), dict(algorithm="pso", pop=20, iters=40, encoding="waypoints")),
  ("circle gwo waypoints penalty", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="gwo", pop=20, iters=40,
                                                                    encoding="waypoints", constraint="penalty")),
  ("grid pso (spline)", gw, gs, gg, dict(encoding="paper", algorithm="pso", pop=20, iters=40)),
  ("grid gwo spline", hw, hs, hg, dict(algorithm="gwo", pop=20, iters=40, encoding="spline")),
  ("circle gwo spline li2023", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="gwo", pop=20, iters=40,
                                                                preset="li2023")),
  ("grid gwo general", hw, hs, hg, dict(algorithm="gwo", pop=20, iters=40, encoding="general")),
  ("grid gwo general li2023", gw, gs, gg, dict(algorithm="gwo", pop=20, iters=40, encoding="general",
                                               preset="li2023")),
  ("circle gwo general", cw, (0.5, 0.5), (9.5, 9.5), dict(algorithm="gwo", pop=20, iters=40, encoding="general")),
  ("grid woa general clearance", gw, gs, gg, dict(algorithm="woa", pop=20, iters=40, encoding="general",
                                                  clearance=0.2)),
  ("grid gwo budget", gw, gs, gg, dict(encoding="paper", algorithm="gwo", pop=10, budget=Budget(iterations=60, stagnation=8))),
  ("circle pso budget evals", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="pso", pop=10,
                                                               budget=Budget(evaluations=333))),
  # the QP smoother on more maps (its Hessian is derived from the smoothing energy)
  ("grid missa refine qp", hw, hs, hg, dict(encoding="paper", algorithm="missa", pop=20, iters=40, refine="qp")),
  ("grid astar refine qp", gw, gs, gg, dict(algorithm="astar", refine="qp")),
  ("circle ipso refine qp", cw, (0.5, 0.5), (9.5, 9.5), dict(encoding="paper", algorithm="ipso", pop=20, iters=40, refine="qp")),
]
only = sys.argv[2:]  # optional case names: run only these
out = {}
for name, w, s, g, kw in cases:
    if only and name not in only:
        continue
    r = op.plan(w, s, g, seed=0, **kw)
    hh, keep = h(r)
    out[name] = keep
    print(f"{name:<28} {hh} len={r.length:.6f} feas={r.feasible} refined={r.refined}")
json.dump(out, open(sys.argv[1], "w"), default=float)
