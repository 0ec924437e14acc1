"""Writes the IGES files of this folder with Open CASCADE (OCP, cadquery-ocp-novtk) and prints
the values the Rust tests compare against (crates/spline-io/tests/integration/iges/occt.rs, `occt_*` tests).

    target/python-venv/bin/python crates/spline-io/tests/data/iges/occt_write.py crates/spline-io/tests/data/iges
"""
import json, math, sys
from OCP.gp import gp_Pnt, gp_Ax2, gp_Dir
from OCP.OCP.collections import (Array1_gp_Pnt as TColgp_Array1OfPnt, Array2_gp_Pnt as TColgp_Array2OfPnt,
                                 Array1_double as TColStd_Array1OfReal, Array1_int as TColStd_Array1OfInteger)
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
from OCP.BRepFilletAPI import BRepFilletAPI_MakeFillet
from OCP.TopExp import TopExp_Explorer
from OCP.TopAbs import TopAbs_EDGE
from OCP.TopoDS import TopoDS, TopoDS_Compound
from OCP.BRep import BRep_Builder
from OCP.IGESControl import IGESControl_Writer, IGESControl_Controller
from OCP.Interface import Interface_Static

out = sys.argv[1]
IGESControl_Controller.Init_s()
Interface_Static.SetIVal_s("write.iges.brep.mode", 1)  # B-rep (186/514/510/508/504/502)

def arr1(values, cls):
    a = cls(1, len(values))
    for i, v in enumerate(values):
        a.SetValue(i + 1, v)
    return a

# A rational cubic curve: knots 0, 0.4 (x2), 1; 6 poles.
poles = [(0, 0, 0), (1, 2, 0.5), (2, -1, 0.25), (3, 0.5, 1), (4, 1, -1), (5, 0, 0)]
cp = TColgp_Array1OfPnt(1, len(poles))
for i, p in enumerate(poles):
    cp.SetValue(i + 1, gp_Pnt(*p))
weights = [1.0, 0.5, 2.0, 1.5, 0.75, 1.0]
curve = Geom_BSplineCurve(cp, arr1(weights, TColStd_Array1OfReal), arr1([0.0, 0.4, 1.0], TColStd_Array1OfReal),
                          arr1([4, 2, 4], TColStd_Array1OfInteger), 3)
edge = BRepBuilderAPI_MakeEdge(curve).Edge()

# A polynomial surface: degrees (2, 1), 4 x 3 poles, P(i, j) = (i, j, i * j + 0.1 i^2).
sp = TColgp_Array2OfPnt(1, 4, 1, 3)
for i in range(4):
    for j in range(3):
        sp.SetValue(i + 1, j + 1, gp_Pnt(i, j, i * j + 0.1 * i * i))
surface = Geom_BSplineSurface(sp, arr1([0.0, 0.5, 1.0], TColStd_Array1OfReal), arr1([0.0, 0.5, 1.0], TColStd_Array1OfReal),
                              arr1([3, 1, 3], TColStd_Array1OfInteger), arr1([2, 1, 2], TColStd_Array1OfInteger), 2, 1)
face = BRepBuilderAPI_MakeFace(surface, 1e-7).Face()

compound = TopoDS_Compound()
builder = BRep_Builder()
builder.MakeCompound(compound)
builder.Add(compound, edge)
builder.Add(compound, face)
w = IGESControl_Writer("MM", 1)
w.AddShape(compound)
w.ComputeModel()
w.Write(f"{out}/occt_bspline.igs")

# A box with one filleted edge and a cylinder.
box = BRepPrimAPI_MakeBox(10.0, 20.0, 30.0).Shape()
fillet = BRepFilletAPI_MakeFillet(box)
ex = TopExp_Explorer(box, TopAbs_EDGE)
fillet.Add(2.0, TopoDS.Edge(ex.Current()))
shape = fillet.Shape()
cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(50, 0, 0), gp_Dir(0, 0, 1)), 3.0, 7.0).Shape()
compound = TopoDS_Compound()
builder.MakeCompound(compound)
builder.Add(compound, shape)
builder.Add(compound, cyl)
w = IGESControl_Writer("MM", 1)
w.AddShape(compound)
w.ComputeModel()
w.Write(f"{out}/occt_fillet_box.igs")

print(json.dumps({"curve_point_0.3": list(curve.Value(0.3).Coord()),
                  "surface_point_0.3_0.7": list(surface.Value(0.3, 0.7).Coord())}))
