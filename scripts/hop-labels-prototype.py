#!/usr/bin/env python3
"""Hop-indexed distance labels, a measurement prototype (not a netspec family; docs/benchmarks.md,
*Hop-indexed distance labels*).

Usage: scripts/hop-labels-prototype.py MODEL.mps K LAMBDA [TIME_LIMIT]

MODEL.mps is a strong-recipe export with the distance flow (`netspec solve SPEC --no-solve
--export MODEL.mps`; `netspec solve SPEC --relax` gives its own LP bound). The distance flow's
costs are set to 0 and the λD term is carried instead by labels x[v,k] (vertex v active at hop
distance k = 1..K from the sinks), parent arcs a[v→u,k] (a ≤ E_e, a ≤ x[u,k−1], a ≤ x[v,k],
Σ_u a[v→u,k] ≥ x[v,k], at most E_e arcs per edge) and per-edge levels z[e,k] (Σ_k z[e,k] = E_e,
z[e,k] ≤ x[u,k] + x[v,k], cost LAMBDA·k, LAMBDA = λD × the uniform edge length). K must bound
every label of some optimum: LAMBDA·K(K−1)/2 ≤ an incumbent's objective does (a vertex at hop
distance n pays LAMBDA·(0 + 1 + … + n−1) along its shortest path). Without TIME_LIMIT the LP
relaxation is solved (every column continuous); with it, HiGHS solves the MIP (labels binary,
2 threads, parallel=on, mip_pscost_minreliable=0 as the strong recipe hands HiGHS) and logs to
hop-labels-mip.log. Needs `pip install highspy`.

The mesh is read back from the export's names: H_v<u>_v<v> (direction binaries, cost 0 exactly
when the head is a sink), their row dir_e<e> (the edge), E_e<e> and V_v<v>.
"""
import re, sys, time
import highspy

if len(sys.argv) not in (4, 5):
    sys.exit(__doc__.split("\n\n")[1])
path, K, lam = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
time_limit = float(sys.argv[4]) if len(sys.argv) == 5 else None
INF = highspy.kHighsInf

h = highspy.Highs()
h.setOptionValue("output_flag", False)
if h.readModel(path) != highspy.HighsStatus.kOk:
    sys.exit(f"{path}: HiGHS could not read it")
lp = h.getLp()
col = {name: i for i, name in enumerate(lp.col_names_)}
a_start, a_index, row_names = lp.a_matrix_.start_, lp.a_matrix_.index_, lp.row_names_

# Edges and sinks from the direction binaries H_v<u>_v<v> and their rows dir_e<e>.
edges, sinks = {}, set()
for name, i in col.items():
    m = re.match(r"H_v(\d+)_v(\d+)$", name)
    if not m:
        continue
    u, v = int(m[1]), int(m[2])
    if lp.col_cost_[i] == 0:
        sinks.add(v)
    for p in range(a_start[i], a_start[i + 1]):
        r = row_names[a_index[p]]
        if r.startswith("dir_e"):
            edges.setdefault(int(r[5:]), (u, v))
if not edges:
    sys.exit(f"{path}: no H_v…_v… columns with dir_e… rows: not a strong-recipe export with the distance flow")
print("edges", len(edges), "sinks", len(sinks), "V", sum(n.startswith("V_v") for n in col))

for name, i in col.items():  # the distance flow keeps its rows, loses its costs
    if name.startswith(("F_", "H_")):
        h.changeColCost(i, 0.0)

def new_var(cost=0.0):
    h.addVar(0.0, 1.0)
    j = h.getNumCol() - 1
    if cost:
        h.changeColCost(j, cost)
    return j

def le(cols, coefs):  # Σ coefs·cols ≤ 0
    h.addRow(-INF, 0.0, len(cols), cols, coefs)

neighbours = {}
for e, (u, v) in edges.items():
    neighbours.setdefault(u, []).append((v, e))
    neighbours.setdefault(v, []).append((u, e))
non_sinks = [v for v in sorted(neighbours) if v not in sinks]

x = {}  # x[v,k]: Σ_k x[v,k] = V_v
for v in non_sinks:
    for k in range(1, K + 1):
        x[v, k] = new_var()
        if time_limit is not None:
            h.changeColIntegrality(x[v, k], highspy.HighsVarType.kInteger)
    h.addRow(0.0, 0.0, K + 1, [x[v, k] for k in range(1, K + 1)] + [col[f"V_v{v}"]], [1.0] * K + [-1.0])

SINK = "sink"
def label(v, k):  # x[v,k], SINK for a sink at level 0 (a constant 1), None where no such label
    if v in sinks:
        return SINK if k == 0 else None
    return x.get((v, k))

arcs_on = {}  # parent arcs per edge
for v in non_sinks:
    for k in range(1, K + 1):
        arcs = []
        for u, e in neighbours[v]:
            parent = label(u, k - 1)
            if parent is None:
                continue
            a = new_var()
            arcs.append(a)
            arcs_on.setdefault(e, []).append(a)
            le([a, col[f"E_e{e}"]], [1.0, -1.0])
            if parent != SINK:
                le([a, parent], [1.0, -1.0])
            le([a, x[v, k]], [1.0, -1.0])
        h.addRow(0.0, INF, len(arcs) + 1, arcs + [x[v, k]], [1.0] * len(arcs) + [-1.0])

for e, (u, v) in edges.items():
    E = col[f"E_e{e}"]
    arcs = arcs_on.get(e, [])
    le(arcs + [E], [1.0] * len(arcs) + [-1.0])
    levels = []
    for k in range(K + 1):
        ends = [t for t in (label(u, k), label(v, k)) if t is not None]
        if not ends:
            continue
        z = new_var(lam * k)
        levels.append(z)
        if SINK not in ends:
            le([z] + ends, [1.0] + [-1.0] * len(ends))
    h.addRow(0.0, 0.0, len(levels) + 1, levels + [E], [1.0] * len(levels) + [-1.0])
print("cols", h.getNumCol(), "rows", h.getNumRow())

start = time.time()
if time_limit is not None:
    for option, value in [("output_flag", True), ("time_limit", time_limit), ("threads", 2),
                          ("mip_pscost_minreliable", 0), ("parallel", "on"), ("log_file", "hop-labels-mip.log")]:
        h.setOptionValue(option, value)
    h.run()
    info = h.getInfo()
    print("MIP", K, info.objective_function_value, info.mip_dual_bound, info.mip_gap,
          "%.1fs" % (time.time() - start), info.mip_node_count)
else:
    for j in range(h.getNumCol()):
        h.changeColIntegrality(j, highspy.HighsVarType.kContinuous)
    h.run()
    print("LP", K, h.getInfo().objective_function_value, "%.1fs" % (time.time() - start))
