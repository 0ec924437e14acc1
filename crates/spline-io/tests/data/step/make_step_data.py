"""Writes the STEP files of crates/spline-io/tests/data/step with Open CASCADE 8 (PyPI
cadquery-ocp-novtk): a 10 x 20 x 30 box with one edge filleted (radius 2), a cylinder of
radius 3 and height 7, a sphere of radius 2 and a torus (5, 1) about z, each as a solid.
Run: python make_step_data.py OUT_DIR"""
import sys
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakeSphere, BRepPrimAPI_MakeTorus, BRepPrimAPI_MakeCone
from OCP.BRepFilletAPI import BRepFilletAPI_MakeFillet
from OCP.TopExp import TopExp_Explorer
from OCP.TopAbs import TopAbs_EDGE
from OCP.TopoDS import TopoDS
from OCP.STEPControl import STEPControl_Writer, STEPControl_AsIs

out = sys.argv[1]
box = BRepPrimAPI_MakeBox(10, 20, 30).Shape()
fillet = BRepFilletAPI_MakeFillet(box)
fillet.Add(2.0, TopoDS.Edge(TopExp_Explorer(box, TopAbs_EDGE).Current()))
shapes = {
    "fillet_box": fillet.Shape(),
    "cylinder": BRepPrimAPI_MakeCylinder(3, 7).Shape(),
    "sphere": BRepPrimAPI_MakeSphere(2).Shape(),
    "torus": BRepPrimAPI_MakeTorus(5, 1).Shape(),
    "cone": BRepPrimAPI_MakeCone(3, 1, 4).Shape(),
}
for name, shape in shapes.items():
    w = STEPControl_Writer()
    w.Transfer(shape, STEPControl_AsIs)
    w.Write(f"{out}/{name}.step")
