"""OpenCASCADE's view of a STEP or IGES file written by `vesselcad export`.

Usage: python check_exchange.py FILE.step|FILE.igs SAMPLES

Reads the file with OCCT's STEP reader (STEPControl_Reader) or, for .igs, its
IGES reader (IGESControl_Reader), default settings, and prints one JSON object: how many roots transferred and whether any entity
failed, BRepCheck_Analyzer's verdict on the whole shape and per shell, the
free edges OCCT finds (ShapeAnalysis_FreeBounds) and what BRepBuilderAPI_Sewing
would still sew, each face's name (from the STEP entity it came from), area
and SAMPLES x SAMPLES points of its surface (u, v, x, y, z) over the face's
parameter box (no face list for SAMPLES 0), and each product's name (STEP) or each group's name and level (IGES). The Rust test compares these with
vesselcad's own NURBS.
"""

import json
import sys

from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepTools import BRepTools
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.Interface import Interface_Static
from OCP.ShapeAnalysis import ShapeAnalysis_FreeBounds
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS


def count(shape, kind):
    n = 0
    explorer = TopExp_Explorer(shape, kind)
    while explorer.More():
        n += 1
        explorer.Next()
    return n


def main():
    path, samples = sys.argv[1], int(sys.argv[2])
    iges = path.lower().endswith((".igs", ".iges"))
    reader = IGESControl_Reader() if iges else STEPControl_Reader()
    if iges:
        # One edge per B-spline curve, as STEP: by default OCCT splits a C0
        # curve (a sampled loop of degree 1) at every sample.
        Interface_Static.SetIVal_s("read.iges.bspline.continuity", 0)
    status = reader.ReadFile(path)
    out = {"read": status == IFSelect_RetDone}
    if status != IFSelect_RetDone:
        print(json.dumps(out))
        return
    model = reader.Model()
    check = reader.Model().GlobalCheck()
    out["read_failures"] = check.NbFails()
    out["roots"] = reader.TransferRoots()
    shape = reader.OneShape()
    out["valid"] = BRepCheck_Analyzer(shape).IsValid()
    out["faces"] = count(shape, TopAbs_FACE)
    out["shells"] = count(shape, TopAbs_SHELL)
    out["solids"] = count(shape, TopAbs_SOLID)

    free = ShapeAnalysis_FreeBounds(shape, 1e-6, False, False)
    out["free_edges"] = count(free.GetClosedWires(), TopAbs_EDGE) + count(
        free.GetOpenWires(), TopAbs_EDGE
    )
    sewing = BRepBuilderAPI_Sewing(1e-4)
    sewing.Add(shape)
    sewing.Perform()
    out["sewing_contiguous"] = sewing.NbContigousEdges()
    out["sewing_free"] = sewing.NbFreeEdges()
    out["sewing_multiple"] = sewing.NbMultipleEdges()

    solids = []
    explorer = TopExp_Explorer(shape, TopAbs_SOLID)
    while explorer.More():
        props = GProp_GProps()
        BRepGProp.VolumeProperties_s(explorer.Current(), props, 1e-10)
        solids.append(props.Mass())
        explorer.Next()
    out["solid_volumes"] = solids

    # Each face with the name of the ADVANCED_FACE it came from; its surface
    # placed in the plant (the assembly's placement applied).
    transfer = reader.WS().TransferReader()
    faces = []
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while samples > 0 and explorer.More():
        face = TopoDS.Face(explorer.Current())
        explorer.Next()
        entity = transfer.EntityFromShapeResult(face, -1)
        if entity is None:
            name = None
        elif iges:
            name = entity.NameValue().ToCString() if entity.HasName() else None
        else:
            name = entity.Name().ToCString()
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(face, props, 1e-10)
        surface = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        points = []
        for a in range(samples):
            for b in range(samples):
                u = u0 + (u1 - u0) * (a + 0.5) / samples
                v = v0 + (v1 - v0) * (b + 0.5) / samples
                p = surface.Value(u, v)
                points.append([u, v, p.X(), p.Y(), p.Z()])
        faces.append(
            {
                "name": name,
                "area": props.Mass(),
                "valid": BRepCheck_Analyzer(face).IsValid(),
                "points": points,
            }
        )
    out["face_list"] = faces
    products = []
    for i in range(1, model.NbEntities() + 1):
        entity = model.Value(i)
        kind = entity.DynamicType().Name()
        if kind == "StepBasic_Product":
            products.append(entity.Name().ToCString())
        elif iges and entity.TypeNumber() == 402 and entity.HasName():
            products.append([entity.NameValue().ToCString(), entity.Level()])
    out["products"] = products
    print(json.dumps(out))


main()
