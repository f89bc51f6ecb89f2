#!/usr/bin/env python3
"""Hop-indexed distance labels, a measurement prototype (not a netspec family; docs/benchmarks.md,
*Hop-indexed distance labels*).

Usage: scripts/hop-labels-prototype.py MODEL.mps K LAMBDA [hop|none] [TIME_LIMIT]

MODEL.mps is a strong-recipe export with the distance flow (`netspec solve SPEC --no-solve
--export MODEL.mps`). With `hop`, the distance flow's costs are set to 0 and the λD term is
carried instead by labels x[v,k] (vertex v active at hop distance k = 1..K from the sinks),
parent arcs a[v→u,k] (a ≤ E_e, a ≤ x[u,k−1], a ≤ x[v,k], Σ_u a[v→u,k] ≥ x[v,k], at most E_e
arcs per edge) and per-edge levels z[e,k] (Σ_k z[e,k] = E_e, z[e,k] ≤ x[u,k] + x[v,k], cost
LAMBDA·k, LAMBDA = λD × the uniform edge length). K must bound every label of some optimum:
LAMBDA·K(K−1)/2 ≤ an incumbent's objective does (a vertex at hop distance n pays
LAMBDA·(0 + 1 + … + n−1) along its shortest path). Without TIME_LIMIT the LP relaxation is
solved (every column continuous); with it, HiGHS solves the MIP (labels binary, 2 threads,
parallel=on, mip_pscost_minreliable=0 as the strong recipe hands HiGHS) and logs to
hop-labels-mip.log. `none` solves the exported model's LP unchanged. Needs `pip install highspy`.
"""
import highspy, re, sys, math, time
path=sys.argv[1]; K=int(sys.argv[2]); lam=float(sys.argv[3]) if len(sys.argv)>3 else 1.0
mode=sys.argv[4] if len(sys.argv)>4 else "hop"
MIP=len(sys.argv)>5
TL=float(sys.argv[5]) if MIP else 0
h=highspy.Highs(); h.setOptionValue("output_flag",False); h.readModel(path)
lp=h.getLp(); n=lp.num_col_; names=lp.col_names_
idx={nm:i for i,nm in enumerate(names)}
cost=list(lp.col_cost_)
# edges from H vars
edges={}  # e -> (u,v)
hcols={}
for nm,i in idx.items():
    m=re.match(r"H_v(\d+)_v(\d+)$",nm)
    if m: hcols[(int(m[1]),int(m[2]))]=i
# map H pair to E via dir rows: use A matrix
A=lp.a_matrix_; # column-wise
starts=A.start_; index=A.index_; value=A.value_
rownames=lp.row_names_
dirrow={}
for (u,v),i in hcols.items():
    for p in range(starts[i],starts[i+1]):
        r=rownames[index[p]]
        if r.startswith("dir_e"): dirrow[(u,v)]=int(r[5:])
sinkhead=set()
for (u,v),i in hcols.items():
    if cost[i]==0: sinkhead.add(v)
sinks=sinkhead
for (u,v),e in dirrow.items():
    if u<v or (v,u) not in dirrow: edges[e]=(u,v)
Vcol={int(nm[3:]):i for nm,i in idx.items() if nm.startswith("V_v")}
Ecol={e:idx[f"E_e{e}"] for e in edges}
print("edges",len(edges),"sinks",len(sinks),"V",len(Vcol))
if mode=="none":
    pass
else:
  # zero distance costs
  for nm,i in idx.items():
    if nm.startswith("F_") or nm.startswith("H_"): h.changeColCost(i,0.0)
  nbr={}
  for e,(u,v) in edges.items():
    nbr.setdefault(u,[]).append((v,e)); nbr.setdefault(v,[]).append((u,e))
  verts=sorted(set(nbr))
  nonsink=[v for v in verts if v not in sinks]
  def newvar(c=0.0,lb=0.0,ub=1.0):
    h.addVar(lb,ub); j=h.getNumCol()-1
    if c: h.changeColCost(j,c)
    return j
  x={}
  for v in nonsink:
    for k in range(1,K+1):
      x[v,k]=newvar()
      if MIP: h.changeColIntegrality(x[v,k], highspy.HighsVarType.kInteger)
    cols=[x[v,k] for k in range(1,K+1)]+[Vcol[v]]
    h.addRow(0,0,len(cols),cols,[1.0]*K+[-1.0])
  def xv(v,k):
    if v in sinks: return "one" if k==0 else None
    return x.get((v,k))
  a={}
  arcs_of={}
  for v in nonsink:
    for k in range(1,K+1):
      arcs=[]
      for (u,e) in nbr[v]:
        xu=xv(u,k-1)
        if xu is None: continue
        j=newvar(); a[v,u,k]=j; arcs.append(j); arcs_of.setdefault(e,[]).append(j)
        h.addRow(-highspy.kHighsInf,0,2,[j,Ecol[e]],[1.0,-1.0])
        if xu!="one": h.addRow(-highspy.kHighsInf,0,2,[j,xu],[1.0,-1.0])
        h.addRow(-highspy.kHighsInf,0,2,[j,x[v,k]],[1.0,-1.0])
      h.addRow(0,highspy.kHighsInf,len(arcs)+1,arcs+[x[v,k]],[1.0]*len(arcs)+[-1.0])
  for e,(u,v) in edges.items():
    # parent arcs on e at most E
    cols=arcs_of.get(e,[])
    h.addRow(-highspy.kHighsInf,0,len(cols)+1,cols+[Ecol[e]],[1.0]*len(cols)+[-1.0])
    zs=[]
    for k in range(0,K+1):
      ends=[xv(u,k),xv(v,k)]
      if all(t is None for t in ends): continue
      z=newvar(lam*k); zs.append(z)
      if "one" in ends: continue
      cs=[t for t in ends if t is not None]
      h.addRow(-highspy.kHighsInf,0,len(cs)+1,[z]+cs,[1.0]+[-1.0]*len(cs))
    h.addRow(0,0,len(zs)+1,zs+[Ecol[e]],[1.0]*len(zs)+[-1.0])
print("cols",h.getNumCol(),"rows",h.getNumRow())
if MIP:
  h.setOptionValue("output_flag",True); h.setOptionValue("time_limit",TL); h.setOptionValue("threads",2)
  h.setOptionValue("mip_pscost_minreliable",0); h.setOptionValue("parallel","on")
  h.setOptionValue("log_file","hop-labels-mip.log")
  t=time.time(); h.run(); i=h.getInfo()
  print("MIP",mode,K,i.objective_function_value,i.mip_dual_bound,i.mip_gap,"%.1fs"%(time.time()-t), i.mip_node_count)
else:
  nc=h.getNumCol()
  for j in range(nc): h.changeColIntegrality(j, highspy.HighsVarType.kContinuous)
  t=time.time(); h.run(); print("LP",mode,K,h.getInfo().objective_function_value, "%.1fs"%(time.time()-t))
