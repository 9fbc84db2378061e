"""The files of a mesh besides mesh.msh (which gmsh writes): mesh.inp, the layout of
rve.inp on the tetrahedra or (2D) the triangles, and mesh.vtu."""

import math

from mesh_common import MeshError, on_plane, percentile

def write_list(f, header, ids):
    f.write(header + "\n")
    ids = list(ids)
    for i in range(0, len(ids), 16):
        f.write(", ".join(str(n) for n in ids[i:i + 16]) + "\n")


# CalculiX reads at most 20 characters per number of a data line.
CCX_FIELD = 20


def num(x):
    """x in at most CCX_FIELD characters: repr when it fits (it reads back exactly),
    else fewer significant digits (a tiny coordinate such as -1.907386087041541e-05)."""
    text = repr(float(x))
    digits = 16
    while len(text) > CCX_FIELD:
        text = "%.*g" % (digits, x)
        digits -= 1
    return text


# The plane-strain sections' thickness (PLANE_THICKNESS of rve.inp): forces are per
# unit thickness.
PLANE_THICKNESS = 1.0


def write_inp(path, job, coords, elements, images, origin):
    """mesh.inp: the layout of rve.inp (src/io/decks/abaqus.rs) on the tetrahedra (C3D4
    or C3D10), or in 2D (two lengths in the job's box) on the triangles: CPE3 or CPE6,
    plane-strain sections of thickness 1 and rve.inp's own plane step (the job's
    plane_step, written by pack). One writer for both: only the element, the heading,
    the sections and the step differ."""
    size = job["box"]
    dims = len(size)
    plane = dims == 2
    element = (("CPE3", "CPE6") if plane else ("C3D4", "C3D10"))[job["order"] - 1]
    n_nodes = len(coords)
    rp = [n_nodes + 1 + d for d in range(dims)]
    rp_names = ["RPX", "RPY", "RPZ"][:dims]
    lengths = " x ".join(repr(x) for x in size)
    at = ", ".join(repr(x) for x in origin[:dims])
    with open(path, "w") as f:
        f.write("*Heading\n")
        # tools/ccx_plane.py reads the rectangle's lengths from this line.
        what = (f"{element} elements (plane strain, thickness 1), rectangle" if plane
                else f"{element} elements, box")
        f.write(f"grainpack conforming mesh: {len(elements)} {what} {lengths} "
                f"{job['length_unit']} from ({at}), "
                f"{'periodic' if job['periodic'] else 'not periodic'}\n")
        f.write(f"** units (the scene's [units]): lengths in {job['length_unit']}, "
                f"stresses and E in {job['stress_unit']}, forces in "
                f"{job['stress_unit']}*{job['length_unit']}^2\n")
        f.write("** nodes and elements numbered as in mesh.msh; element sets GRAIN_<id> "
                "(grains.csv's id), one per phase and the matrix\n*Node\n")
        for n in range(1, n_nodes + 1):
            f.write(f"{n}, " + ", ".join(num(x) for x in coords[n][:dims]) + "\n")
        for d in range(dims):
            corner = list(origin[:dims])
            corner[d] += size[d]
            f.write(f"{rp[d]}, " + ", ".join(num(x) for x in corner) + "\n")
        f.write(f"*Element, type={element}\n")
        for e, (_, conn, _, _) in enumerate(elements):
            f.write(f"{e + 1}, " + ", ".join(str(n) for n in conn) + "\n")
        by_grain, by_phase = {}, {}
        for e, (grain, _, _, _) in enumerate(elements):
            key = None if grain is None else grain["id"]
            by_grain.setdefault(key, []).append(e + 1)
            phase = job["matrix_phase"] if grain is None else grain["phase"]
            by_phase.setdefault(phase, []).append(e + 1)
        for g in sorted(k for k in by_grain if k is not None):
            write_list(f, f"*Elset, elset=GRAIN_{g}", by_grain[g])
        for m in job["materials"]:
            if m["phase"] in by_phase:
                write_list(f, f"*Elset, elset={m['name']}", by_phase[m["phase"]])
        write_node_sets(f, coords, origin, size)
        for name, id_ in zip(rp_names, rp):
            f.write(f"*Nset, nset={name}\n{id_}\n")
        f.write("*Nset, nset=RP\n" + ", ".join(rp_names) + "\n")
        if job["periodic"]:
            f.write("*Equation\n")
            for node in sorted(images):
                image, far = images[node]
                for dof in range(1, dims + 1):
                    terms = [(node, 1.0), (image, -1.0)] + [(rp[d], -1.0) for d in far]
                    f.write(f"{len(terms)}\n")
                    for i in range(0, len(terms), 4):
                        f.write(", ".join(f"{n}, {dof}, {c!r}" for n, c in terms[i:i + 4])
                                + "\n")
        for m in job["materials"]:
            if m["phase"] not in by_phase:
                continue
            f.write(f"*Material, name={m['name']}\n*Elastic\n{m['young']!r}, {m['poisson']!r}\n")
            f.write(f"*Solid Section, elset={m['name']}, material={m['name']}\n")
            if plane:
                f.write(f"{PLANE_THICKNESS!r}\n")
        if plane:
            f.write(job["plane_step"])
        else:
            write_solid_step(f, job, size)


def write_solid_step(f, job, size):
    """The uniaxial step of rve.inp in 3D: periodic through the reference nodes, or
    on the faces of a walled box."""
    strain = job["strain"]
    f.write(f"{job['step_marker']}: uniaxial strain {strain:e} along x\n")
    f.write("*Boundary\n1, 1, 3, 0.0\n*Step\n*Static\n*Boundary\n")
    if job["periodic"]:
        f.write(f"RPX, 1, 1, {strain * size[0]!r}\n")
        f.write("RPX, 2, 3, 0.0\nRPY, 1, 1, 0.0\nRPY, 3, 3, 0.0\nRPZ, 1, 2, 0.0\n")
        f.write("*Node Print, nset=RP\nU\n*Node Print, nset=X1, totals=only\nRF\n")
    else:
        f.write("X0, 1, 1, 0.0\nY0, 2, 2, 0.0\nZ0, 3, 3, 0.0\n")
        f.write(f"X1, 1, 1, {strain * size[0]!r}\n")
        f.write("*Node Print, nset=X1, totals=only\nRF\n")
    f.write("*End Step\n")


def write_node_sets(f, coords, origin, size):
    """Faces X0 ... Z1, edges X0Y0 ..., corners X0Y0Z0 ..., as in rve.inp; in 2D (two
    lengths in `size`) the edges X0 ... Y1 and the corners X0Y0 ..."""
    axes = len(size)
    length = max(size)
    side = {}
    for n, p in coords.items():
        s = []
        for d in range(axes):
            if on_plane(p[d], origin[d], length):
                s.append(1)
            elif on_plane(p[d], origin[d] + size[d], length):
                s.append(2)
            else:
                s.append(0)
        side[n] = s
    for fixed in range(1, axes + 1):
        for mask in range(3 ** axes):
            sides = [(mask // 3 ** d) % 3 for d in range(axes)]
            if sum(1 for s in sides if s) != fixed:
                continue
            name = "".join(f"{'XYZ'[d]}{sides[d] - 1}" for d in range(axes) if sides[d])
            ids = [n for n in sorted(coords)
                   if all(sides[d] == 0 or side[n][d] == sides[d] for d in range(axes))]
            write_list(f, f"*Nset, nset={name}", ids)


# VTK's cell type and nodes per cell by (dimension, order): tetrahedra, triangles.
VTK_CELLS = {(3, 1): (10, 4), (3, 2): (24, 10), (2, 1): (5, 3), (2, 2): (22, 6)}


def write_vtu(path, coords, elements, order, phases, dimension=3):
    """mesh.vtu: the tetrahedra (triangles in the plane z = 0 in 2D) with cell data
    grain (-1: matrix), phase (the matrix is phase `phases`, as in rve.vti) and SICN.
    `coords` holds three coordinates per node."""
    vtk_type, npe = VTK_CELLS[(dimension, order)]
    n_nodes = len(coords)
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
                'byte_order="LittleEndian" header_type="UInt64">\n<UnstructuredGrid>\n')
        f.write(f'<Piece NumberOfPoints="{n_nodes}" NumberOfCells="{len(elements)}">\n')
        f.write('<Points>\n<DataArray type="Float64" NumberOfComponents="3" '
                'format="ascii">\n')
        for n in range(1, n_nodes + 1):
            f.write("%r %r %r\n" % coords[n])
        f.write("</DataArray>\n</Points>\n<Cells>\n")
        f.write('<DataArray type="Int64" Name="connectivity" format="ascii">\n')
        for _, conn, _, _ in elements:
            f.write(" ".join(str(n - 1) for n in conn) + "\n")
        f.write('</DataArray>\n<DataArray type="Int64" Name="offsets" format="ascii">\n')
        f.write(" ".join(str(npe * (i + 1)) for i in range(len(elements))) + "\n")
        f.write('</DataArray>\n<DataArray type="UInt8" Name="types" format="ascii">\n')
        f.write(" ".join([str(vtk_type)] * len(elements)) + "\n")
        f.write("</DataArray>\n</Cells>\n<CellData>\n")
        f.write('<DataArray type="Int32" Name="grain" format="ascii">\n')
        f.write(" ".join(str(-1 if g is None else g["id"]) for g, _, _, _ in elements) + "\n")
        f.write('</DataArray>\n<DataArray type="Int32" Name="phase" format="ascii">\n')
        f.write(" ".join(str(phases if g is None else g["phase"]) for g, _, _, _ in elements)
                + "\n")
        f.write('</DataArray>\n<DataArray type="Float64" Name="sicn" format="ascii">\n')
        f.write(" ".join(repr(q) for _, _, q, _ in elements) + "\n")
        f.write("</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")



def finish(gmsh, job, coords, elements, images, origin, report):
    """Refuses inverted elements, writes mesh.msh (gmsh), mesh.inp and mesh.vtu, and
    returns summary.json's mesh block: the `report` entries (times, retry, margins,
    face pairs, largest snap, middle nodes straightened) among the counts, the quality and each phase's volume
    (area in 2D) fraction against the packing's exact one."""
    sicn = sorted(q for _, _, q, _ in elements)
    inverted = sum(1 for q in sicn if q <= 0.0)
    if inverted:
        raise MeshError(f"{inverted} of {len(sicn)} elements are inverted (SICN <= 0)")
    size = job["box"]
    dims = len(size)
    files = job["files"]
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(files["msh"])
    write_inp(files["inp"], job, coords, elements, images, origin)
    write_vtu(files["vtu"], coords, elements, job["order"], job["matrix_phase"],
              dimension=dims)
    box = math.prod(size)
    phases, exact = {}, {}
    for grain, _, _, measure in elements:
        p = job["matrix_phase"] if grain is None else grain["phase"]
        phases[p] = phases.get(p, 0.0) + measure
    for g in job["grains"]:
        a = g["semi_axes"]
        own = math.pi * a[0] * a[1] if dims == 2 else 4.0 / 3.0 * math.pi * a[0] * a[1] * a[2]
        exact[g["phase"]] = exact.get(g["phase"], 0.0) + own
    if job.get("fill") != "grains":
        exact[job["matrix_phase"]] = box - sum(exact.values())
    return {
        "elements": len(elements),
        "nodes": len(coords),
        "order": job["order"],
        "element_size": job["element_size"],
        "min_sicn": sicn[0],
        "p1_sicn": percentile(sicn, 0.01),
        "geometry_seconds": report["geometry_seconds"],
        "mesh_seconds": report["mesh_seconds"],
        "retried_with_curvature": report["retried"],
        "first_attempt_error": report.get("first_error"),
        "surface_repairs": report.get("repairs", []),
        "origin": origin,
        "face_margin": report["margins"] if job["periodic"] else None,
        "periodic_face_pairs": report["pairs"],
        "periodic_nodes": len(images),
        "largest_snap": report["worst"],
        "straightened_middle_nodes": report.get("straightened", 0),
        "phase_volume_fractions": [
            {"phase": p, "mesh": phases.get(p, 0.0) / box, "exact": exact.get(p, 0.0) / box}
            for p in sorted(set(phases) | set(exact))
        ],
        "gmsh": gmsh.__version__,
    }
