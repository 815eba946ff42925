"""Exact facet minimum (signed isotropic wrench radius) of the available wrench set
{W t : t_min <= t <= t_max} for DOF 2 or 3, in rational arithmetic: every subset of DOF - 1
generators (cables with t_min < t_max and a non-zero column) gives a facet normal (a perpendicular
or a cross product, exact), and the support function sum_j max(c.w_j t_min_j, c.w_j t_max_j) is
exact; only the final division by |c| is rounded. Independent of the Rust code; used for the
expected values of crates/cdpr-polytope/tests/it/fuzz_regressions.rs.

Usage: echo '{"W": [[row 1], [row 2]], "tmin": [...], "tmax": [...]}' | python3 zonotope_radius.py
"""
import sys, json, itertools, math
from fractions import Fraction as F
def radius(W, tmin, tmax):
    m=len(W); n=len(W[0])
    cols=[[F(W[i][j]) for i in range(m)] for j in range(n)]
    lo=[F(x) for x in tmin]; hi=[F(x) for x in tmax]
    gens=[j for j in range(n) if hi[j]>lo[j] and any(cols[j])]
    best=None
    for S in itertools.combinations(gens, m-1):
        if m==2:
            a=cols[S[0]]; c=[-a[1],a[0]]
        elif m==3:
            a,b=cols[S[0]],cols[S[1]]
            c=[a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]
        if not any(c): continue
        nn=math.sqrt(float(sum(x*x for x in c)))
        for sgn in (1,-1):
            cc=[sgn*x for x in c]
            d=sum(max(sum(cc[i]*cols[j][i] for i in range(m))*lo[j], sum(cc[i]*cols[j][i] for i in range(m))*hi[j]) for j in range(n))
            v=float(d)/nn
            if best is None or v<best: best=v
    return best
if __name__=="__main__":
    d=json.load(sys.stdin)
    print(repr(radius(d["W"],d["tmin"],d["tmax"])))
