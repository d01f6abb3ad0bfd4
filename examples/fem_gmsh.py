"""Gmsh's side of `examples/fem_gmsh.rs`: meshes the surfaces of a STEP file
with quadrilaterals (Frontal-Delaunay recombined by Blossom; Gmsh 4.15.2's
"Frontal-Delaunay for quads" crashes on the drum's STEP;
second order, 8-node quads), one thread, at a given size, and prints one JSON
line: element counts, the minimum scaled Jacobian (Gmsh's minSJ), and the
times of the import and of the 2D mesh.

    target/occt-venv/bin/python examples/fem_gmsh.py FILE.step SIZE_MM
"""

import json
import sys
import time

import gmsh


def main():
    path, size = sys.argv[1], float(sys.argv[2])
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    t0 = time.perf_counter()
    gmsh.model.occ.importShapes(path)
    gmsh.model.occ.synchronize()
    t1 = time.perf_counter()
    gmsh.option.setNumber("Mesh.MeshSizeMin", size)
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)
    gmsh.option.setNumber("Mesh.RecombineAll", 1)
    gmsh.option.setNumber("Mesh.ElementOrder", 2)
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
    gmsh.model.mesh.generate(2)
    t2 = time.perf_counter()
    types, tags, _ = gmsh.model.mesh.getElements(2)
    counts = {}
    every = []
    for kind, ids in zip(types, tags):
        name = gmsh.model.mesh.getElementProperties(kind)[0]
        counts[name] = counts.get(name, 0) + len(ids)
        every.extend(ids)
    quality = gmsh.model.mesh.getElementQualities(every, "minSJ") if every else []
    quads = sum(n for name, n in counts.items() if "Quadrilateral" in name)
    print(
        json.dumps(
            {
                "elements": len(every),
                "quads": quads,
                "counts": counts,
                "min_sj": float(min(quality)) if len(quality) else None,
                "sj_below_0_3": int(sum(1 for q in quality if q < 0.3)),
                "import_s": t1 - t0,
                "mesh_s": t2 - t1,
                "faces": len(gmsh.model.getEntities(2)),
            }
        )
    )
    gmsh.finalize()


if __name__ == "__main__":
    main()
