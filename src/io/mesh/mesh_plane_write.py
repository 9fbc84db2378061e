"""mesh.inp of a 2D mesh: the layout of the plane-strain rve.inp (src/io/decks/abaqus.rs)
on the triangles: CPE3 or CPE6, sections of thickness 1, reference nodes RPX and RPY,
periodic equations on the two in-plane components, and rve.inp's own step template
(the job's plane_step, written by pack)."""

from mesh_write import num, write_list, write_node_sets

# The plane-strain sections' thickness (PLANE_THICKNESS of rve.inp): forces are per
# unit thickness.
PLANE_THICKNESS = 1.0


def write_plane_inp(path, job, coords, elements, images, origin):
    size = job["box"]
    element = "CPE3" if job["order"] == 1 else "CPE6"
    n_nodes = len(coords)
    rp = [n_nodes + 1, n_nodes + 2]
    with open(path, "w") as f:
        f.write("*Heading\n")
        # tools/ccx_plane.py reads the rectangle's lengths from this line.
        f.write(f"grainpack conforming mesh: {len(elements)} {element} elements (plane "
                f"strain, thickness 1), rectangle {size[0]!r} x {size[1]!r} "
                f"{job['length_unit']} from ({origin[0]!r}, {origin[1]!r}), "
                f"{'periodic' if job['periodic'] else 'not periodic'}\n")
        f.write(f"** units (the scene's [units]): lengths in {job['length_unit']}, "
                f"stresses and E in {job['stress_unit']}, forces in "
                f"{job['stress_unit']}*{job['length_unit']}^2\n")
        f.write("** nodes and elements numbered as in mesh.msh; element sets GRAIN_<id> "
                "(grains.csv's id), one per phase and the matrix\n*Node\n")
        for n in range(1, n_nodes + 1):
            x, y, _ = coords[n]
            f.write(f"{n}, {num(x)}, {num(y)}\n")
        for d in range(2):
            at = list(origin)
            at[d] += size[d]
            f.write(f"{rp[d]}, {num(at[0])}, {num(at[1])}\n")
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
        for name, id_ in zip(["RPX", "RPY"], rp):
            f.write(f"*Nset, nset={name}\n{id_}\n")
        f.write("*Nset, nset=RP\nRPX, RPY\n")
        if job["periodic"]:
            f.write("*Equation\n")
            for node in sorted(images):
                image, far = images[node]
                for dof in (1, 2):
                    terms = [(node, 1.0), (image, -1.0)] + [(rp[d], -1.0) for d in far]
                    f.write(f"{len(terms)}\n")
                    for i in range(0, len(terms), 4):
                        f.write(", ".join(f"{n}, {dof}, {c!r}" for n, c in terms[i:i + 4])
                                + "\n")
        for m in job["materials"]:
            if m["phase"] not in by_phase:
                continue
            f.write(f"*Material, name={m['name']}\n*Elastic\n{m['young']!r}, {m['poisson']!r}\n")
            f.write(f"*Solid Section, elset={m['name']}, material={m['name']}\n"
                    f"{PLANE_THICKNESS!r}\n")
        f.write(job["plane_step"])
