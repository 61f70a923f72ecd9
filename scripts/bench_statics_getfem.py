#!/usr/bin/python3
"""GetFEM side of scripts/bench_statics.sh: the same linear elastic block problem.

Usage: /usr/bin/python3 scripts/bench_statics_getfem.py 2d NX NY
       /usr/bin/python3 scripts/bench_statics_getfem.py 3d NX NY NZ

2d: plane strain, box 2 x 1, 8-node serendipity quadrangles (FEM_Q2_INCOMPLETE(2)), u_x = 0 on x = 0,
    u_y = 0 on y = 0, traction P along x on x = LX. E = 210000, nu = 0.3, P = 100.
3d: box 3 x 2 x 1, 20-node serendipity hexahedra (FEM_Q2_INCOMPLETE(3)), symmetry u.n = 0 on the three
    coordinate planes, traction F along x on x = LX. E = 70000, nu = 0.25, F = 50.
The geometry is the regular cartesian (affine) grid; 3 Gauss points per direction as in Code_Aster
(FPG9 / FPG27). Dirichlet conditions with multipliers, MUMPS. The result is checked against the analytic
displacement at the far corner. Prints one line "GETFEM key=value ..." with the phase times in seconds.
"""
import sys
import time

import numpy as np
import getfem as gf

gf.util_trace_level(0)
t_start = time.perf_counter()
case = sys.argv[1]
n = [int(v) for v in sys.argv[2:]]
dim = 2 if case == "2d" else 3
if dim == 2:
    E, NU, P = 210000.0, 0.3, 100.0
    L = [2.0, 1.0]
else:
    E, NU, P = 70000.0, 0.25, 50.0
    L = [3.0, 2.0, 1.0]
assert len(n) == dim

t0 = time.perf_counter()
m = gf.Mesh("cartesian", *[np.linspace(0.0, L[k], n[k] + 1) for k in range(dim)])
# Regions: 1 + k = face x_k = 0, 10 = face x = LX.
for k in range(dim):
    d = [0.0] * dim
    d[k] = -1.0
    m.set_region(1 + k, m.outer_faces_with_direction(d, 0.01))
d = [0.0] * dim
d[0] = 1.0
m.set_region(10, m.outer_faces_with_direction(d, 0.01))
t_mesh = time.perf_counter() - t0

t0 = time.perf_counter()
fem = gf.Fem("FEM_Q2_INCOMPLETE(%d)" % dim)
mfu = gf.MeshFem(m, dim)
mfu.set_fem(fem)
mfm = gf.MeshFem(m, 1)  # multipliers of the normal Dirichlet conditions
mfm.set_fem(fem)
mim = gf.MeshIm(m, gf.Integ("IM_GAUSS_PARALLELEPIPED(%d,5)" % dim))
md = gf.Model("real")
md.add_fem_variable("u", mfu)
lam = E * NU / ((1 + NU) * (1 - 2 * NU))
mu = E / (2 * (1 + NU))
md.add_initialized_data("lambda", [lam])
md.add_initialized_data("mu", [mu])
# In 2D this brick with the 3D lambda is plane strain.
md.add_isotropic_linearized_elasticity_brick(mim, "u", "lambda", "mu")
for k in range(dim):
    md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", mfm, 1 + k)
trac = [0.0] * dim
trac[0] = P
md.add_initialized_data("trac", trac)
md.add_source_term_brick(mim, "u", "trac", 10)
t_setup = time.perf_counter() - t0
ndofs_u = mfu.nbdof()
ndofs = md.nbdof()

t0 = time.perf_counter()
md.assembly()
K = md.tangent_matrix()
rhs = md.rhs()
t_assembly = time.perf_counter() - t0

t0 = time.perf_counter()
x = gf.linsolve_mumps(K, rhs)
md.to_variables(np.asarray(x).ravel())
t_solve = time.perf_counter() - t0

# Check: displacement at the far corner against the analytic solution.
t0 = time.perf_counter()
U = md.variable("u")
nodes = mfu.basic_dof_nodes()
corner = np.array(L)
i = int(np.argmin(np.sum((nodes - corner[:, None]) ** 2, axis=0)))
dofs = [i - (i % dim) + k for k in range(dim)]
got = [U[d] for d in dofs]
if dim == 2:
    want = [(1 - NU**2) * P * L[0] / E, -NU * (1 + NU) * P * L[1] / E]
else:
    want = [P * L[0] / E, -NU * P * L[1] / E, -NU * P * L[2] / E]
err = max(abs(g - w) / abs(w) for g, w in zip(got, want))
t_check = time.perf_counter() - t0
ok = err < 1e-6

print(
    "GETFEM case=%s ndofs_u=%d ndofs=%d mesh=%.3f setup=%.3f assembly=%.3f solve=%.3f check=%.3f "
    "total=%.3f relerr=%.2e ok=%s"
    % (case, ndofs_u, ndofs, t_mesh, t_setup, t_assembly, t_solve, t_check,
       time.perf_counter() - t_start, err, "yes" if ok else "NO")
)
sys.exit(0 if ok else 1)
