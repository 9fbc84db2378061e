"""The plane-strain (2D) solves of tools/ccx_solve.py: CalculiX on a plane-strain deck
`pack` writes for a 2D RVE (rve.inp on pixels, CPE4; mesh.inp on the conforming
triangles, CPE3 or CPE6), and the 2D Hashin-Shtrikman bounds.

Four steps replace the deck's template, each imposing the macroscopic strain through
the reference nodes (u(RPX) = H (Lx, 0), u(RPY) = H (0, Ly)); forces are per unit
thickness (the sections' thickness is 1), so a stress is a face's total force over its
length:

- uniaxial x (y): the normal strain along x (y) imposed, the normal stress along y (x)
  free, the shear held at zero: E' = sigma / eps, nu' = -eps_lateral / eps. For an
  isotropic material in plane strain E' = E / (1 - nu^2) and nu' = nu / (1 - nu); for a
  composite isotropic in the plane E' = 4 k mu / (k + mu), the transverse modulus
  measured in plane strain.
- biaxial: equal normal strains eps along x and y, no shear: the transverse
  (plane-strain) bulk modulus k = (sigma_xx + sigma_yy) / (4 eps) (k = lambda + mu).
- shear: eps_xy = gamma / 2 (H_xy = H_yx = gamma / 2): mu = sigma_xy / gamma, with
  sigma_xy the mean of the forces along y on X1 over Ly and along x on Y1 over Lx.

Only the standard library.
"""

import os
import re
import subprocess

STEP_MARKER = "** ---- step template"
# The imposed strain.
STRAIN = 1e-3


def plane_k_mu(e, nu):
    """The transverse (plane-strain) bulk modulus lambda + mu and the shear modulus."""
    return e / (2.0 * (1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu))


def plane_modulus(k, mu):
    """E' = sigma_xx / eps_xx in plane strain with sigma_yy = 0: 4 k mu / (k + mu)."""
    return 4.0 * k * mu / (k + mu)


def hashin_shtrikman_2d(f2, k1, mu1, k2, mu2):
    """The 2D (transverse) Hashin-Shtrikman bounds on k and mu of phase 2 at area fraction
    f2 in phase 1, both isotropic, phase 2 the stiffer in k and mu (Hashin, J. Mech. Phys.
    Solids 13, 119, 1965; Torquato's d-dimensional bounds at d = 2): with the reference
    phase r,

        k = k_r + f_o / (1 / (k_o - k_r) + f_r / (k_r + mu_r))
        mu = mu_r + f_o / (1 / (mu_o - mu_r) + f_r (k_r + 2 mu_r) / (2 mu_r (k_r + mu_r)))

    (o the other phase): the soft phase as reference gives the lower bounds, the stiff
    the upper. Returns ((k_lower, k_upper), (mu_lower, mu_upper))."""
    f1 = 1.0 - f2

    def bound(kr, mur, ko, muo, fo, fr):
        k = kr + fo / (1.0 / (ko - kr) + fr / (kr + mur))
        mu = mur + fo / (1.0 / (muo - mur) + fr * (kr + 2.0 * mur) / (2.0 * mur * (kr + mur)))
        return k, mu

    k_lo, mu_lo = bound(k1, mu1, k2, mu2, f2, f1)
    k_hi, mu_hi = bound(k2, mu2, k1, mu1, f1, f2)
    return (k_lo, k_hi), (mu_lo, mu_hi)


def read_deck(deck):
    """The model part of a 2D deck, its rectangle [Lx, Ly], its element sets' sizes and
    its materials' (E, nu) by name."""
    with open(deck) as f:
        text = f.read()
    model = text.split(STEP_MARKER)[0]
    m = re.search(r"rectangle (\S+) x (\S+) ", model)
    if re.search(r"\*Element, type=CPE[346]\b", model) is None or m is None:
        raise RuntimeError(f"{deck} is not a plane-strain (CPE3, CPE4 or CPE6) deck")
    size = [float(m.group(1)), float(m.group(2))]
    sets, materials, name, material = {}, {}, None, None
    lines = model.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("*Material, name="):
            material = line.split("=", 1)[1].strip()
        if line.startswith("*Elastic"):
            e, nu = (float(v) for v in lines[i + 1].split(","))
            materials[material] = (e, nu)
        if line.startswith("*"):
            name = line.split("elset=")[1].strip() if line.startswith("*Elset") else None
        elif name is not None and line.strip():
            sets[name] = sets.get(name, 0) + len(line.split(","))
    return model, size, sets, materials


def step(name, size, iterative):
    """The boundary conditions of one of the four steps (see the module's docs)."""
    lx, ly = size
    e = STRAIN
    fixed = {
        "x": [("RPX", 1, e * lx), ("RPX", 2, 0.0), ("RPY", 1, 0.0)],
        "y": [("RPY", 2, e * ly), ("RPY", 1, 0.0), ("RPX", 2, 0.0)],
        "biaxial": [("RPX", 1, e * lx), ("RPX", 2, 0.0), ("RPY", 1, 0.0), ("RPY", 2, e * ly)],
        "shear": [("RPX", 1, 0.0), ("RPX", 2, e / 2 * lx), ("RPY", 1, e / 2 * ly), ("RPY", 2, 0.0)],
    }[name]
    static = "*Static, solver=iterative cholesky" if iterative else "*Static"
    lines = ["*Boundary", "1, 1, 2, 0.0", "*Step", static, "*Boundary"]
    lines += [f"{n}, {d}, {d}, {v!r}" for n, d, v in fixed]
    lines += ["*Node Print, nset=RP", "U"]
    lines += ["*Node Print, nset=X1, totals=only", "RF"]
    lines += ["*Node Print, nset=Y1, totals=only", "RF", "*End Step"]
    return "\n".join(lines) + "\n"


def solve(model, size, name, job, iterative):
    """Runs ccx on one step; returns the strains (from RPX, RPY) and the stresses
    [sigma_xx, sigma_yy, sigma_xy from X1, sigma_xy from Y1]."""
    work, base = os.path.split(job)
    with open(job + ".inp", "w") as f:
        f.write(model + step(name, size, iterative))
    run = subprocess.run(["ccx", "-i", base], cwd=work, capture_output=True, text=True)
    if run.returncode != 0 or "ERROR" in run.stdout:
        raise RuntimeError(f"ccx failed on {job}.inp:\n{run.stdout[-2000:]}{run.stderr}")
    with open(job + ".dat") as f:
        lines = [l.split() for l in f if l.strip()]
    u, forces = [], []
    for i, words in enumerate(lines):
        if words[:2] == ["displacements", "(vx,vy,vz)"]:
            u = [[float(v) for v in row[1:3]] for row in lines[i + 1:i + 3]]
        if words[:2] == ["total", "force"]:
            forces.append([float(v) for v in lines[i + 1][:2]])
    if len(u) != 2 or len(forces) != 2:
        raise RuntimeError(f"no displacements or forces in {job}.dat")
    lx, ly = size
    strains = [u[0][0] / lx, u[1][1] / ly]
    (fx1, fy1), (fx2, fy2) = forces
    return strains, [fx1 / ly, fy2 / lx, fy1 / ly, fx2 / lx]


def plane_moduli(deck, work, iterative=False):
    """E'_x, nu'_xy, E'_y, nu'_yx, k and mu of a 2D deck; its element sets' sizes and its
    materials."""
    model, size, sets, materials = read_deck(deck)
    tag = os.path.basename(os.path.dirname(os.path.abspath(deck)))
    out = {}
    for name in ("x", "y", "biaxial", "shear"):
        strains, s = solve(model, size, name, os.path.join(work, f"plane_{tag}_{name}"), iterative)
        if name == "x":
            out["E_x"], out["nu_xy"] = s[0] / strains[0], -strains[1] / strains[0]
        elif name == "y":
            out["E_y"], out["nu_yx"] = s[1] / strains[1], -strains[0] / strains[1]
        elif name == "biaxial":
            out["k"] = (s[0] + s[1]) / (4.0 * STRAIN)
        else:
            out["mu_x1"], out["mu_y1"] = s[2] / STRAIN, s[3] / STRAIN
            out["mu"] = 0.5 * (out["mu_x1"] + out["mu_y1"])
    return out, sets, materials
