"""Writes a STEP file of about SIZE megabytes (default 100): bicubic B-spline surfaces with
random control points, one after another, for timing `spline import` on a large file.

    python tests/occt/big_step.py OUT.step [SIZE_MB]
    /usr/bin/time -f "%e s %M KB" target/release/spline import OUT.step > /dev/null
"""

import random
import sys


def main():
    out_path = sys.argv[1]
    limit = int(float(sys.argv[2]) * 1e6) if len(sys.argv) > 2 else 100_000_000
    random.seed(1)
    with open(out_path, "w") as out:
        out.write("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('big'),'2;1');\n"
                  "FILE_NAME('','',(''),(''),'','','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n")
        next_id, size = 1, 0
        while size < limit:
            lines, rows = [], []
            for _ in range(6):
                row = []
                for _ in range(6):
                    x, y, z = (random.random() for _ in range(3))
                    lines.append(f"#{next_id} = CARTESIAN_POINT('',({x:.15E},{y:.15E},{z:.15E}));\n")
                    row.append(f"#{next_id}")
                    next_id += 1
                rows.append("(" + ",".join(row) + ")")
            lines.append(f"#{next_id} = B_SPLINE_SURFACE_WITH_KNOTS('s{next_id}',3,3,({','.join(rows)}),"
                         ".UNSPECIFIED.,.F.,.F.,.F.,(4,2,4),(4,2,4),(0.,0.5,1.),(0.,0.5,1.),.UNSPECIFIED.);\n")
            next_id += 1
            text = "".join(lines)
            out.write(text)
            size += len(text)
        out.write("ENDSEC;\nEND-ISO-10303-21;\n")


if __name__ == "__main__":
    main()
