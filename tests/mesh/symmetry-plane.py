#!/usr/bin/python3
"""A half model on rollers equals the whole model it is half of, with friction.

usage: symmetry-plane.py --driver "mpiexec -n 1 conefeti" [--half-driver "mpiexec -n 2 conefeti"] --meshes DIR
                         --case foundation|bodies|quarter --law coulomb|tresca [--extra "options of both runs"]

foundation, bodies: the whole model is the paper's brick (0,3)x(0,1)x(0,1), clamped at x = 0, pressed by 40 MPa on
its top and pulled by 2 MPa along x at its free end, on a rigid plane (foundation) or on an elastic slab clamped at
its bottom (bodies), with Coulomb friction F = 0.3 or a Tresca bound of 12 MPa. Its mesh (DIR/brick-mirrored.msh,
DIR/slab-mirrored.msh: write-box-msh.py --mirror y) is symmetric about the plane y = 1/2, so its solution is too.
The half model is the box y >= 1/2 of the same mesh (the generator's box) with u_y = 0 on that plane (fix_y y0).
quarter: a rigid sphere pressed 0.05 into the block (-1,1)x(-1,1)x(0,1) clamped at its base (DIR/block-mirrored.msh:
--mirror xy), against its quarter x, y >= 0 with u_x = 0 on x = 0 and u_y = 0 on y = 0; the sphere touches the
quarter on its symmetry planes and their common axis only.

The friction nodes on a symmetry plane keep contact and friction along the plane, those on the axis are frictionless
(FrictionOnRollers(), src/contact/contactmodel.cxx). So the part carries exactly its share (1/2, 1/4) of the whole
model's contact force: the sum of the normal forces and the resultant along z, and for the half also the friction
resultant along x (the other directions are the rollers'). They are compared to 1e-5 relative (the solves'
tolerance is 1e-6), and for the half so is the node count: the whole model's contact nodes are twice the half's less
the 9 on the plane. Exit 0 when all agree."""
import argparse
import json
import shlex
import subprocess
import sys

LOADS = ("-scene_body0_E 21.2e10 -scene_body0_nu 0.277 -fem_dirichlet primal -scene_body0_fix x0 "
         "-scene_body0_traction_z1 0,0,-4e7 -scene_body0_traction_x1 2e6,0,0 -summary_table 0 -quiet")
HALF_BRICK = "-scene_body0_lower 0,0.5,0 -scene_body0_upper 3,1,1 -scene_body0_cells 12,2,4 -scene_body0_subdomains 3,1,1 -scene_body0_fix_y y0"
HALF_SLAB = ("-scene_body1_lower 0,0.5,-0.501 -scene_body1_upper 3,1,-0.001 -scene_body1_cells 12,2,2 -scene_body1_subdomains 3,1,1 "
             "-scene_body1_fix z0 -scene_body1_fix_y y0 -scene_body1_E 21.2e10 -scene_body1_nu 0.277")
PLANE_NODES = 9  # contact nodes on y = 1/2: x = 1, 1.25, ..., 3
BLOCK = ("-scene_body0_E 1e9 -scene_body0_nu 0.3 -scene_body0_fix z0 -scene_zone0_type foundation -scene_zone0_shape sphere -scene_zone0_face z1 "
         "-scene_zone0_center 0,0,1.95 -scene_zone0_radius 1 -summary_table 0 -quiet")
QUARTER = "-scene_body0_lower 0,0,0 -scene_body0_upper 1,1,1 -scene_body0_cells 4,4,4 -scene_body0_subdomains 2,2,1 -scene_body0_fix_x x0 -scene_body0_fix_y y0"


def laws(law, slip_bound):
    return "-scene_zone0_law coulomb -scene_zone0_friction 0.3" if law == "coulomb" else "-scene_zone0_law tresca -scene_zone0_slip_bound " + slip_bound


def zone(case):
    if case == "foundation":
        return "-scene_zone0_type foundation -scene_zone0_body 0 -scene_zone0_face z0/x>1 -scene_zone0_point 0,0,-1e-3 -scene_zone0_normal 0,0,1"
    return "-scene_zone0_type bodies -scene_zone0_body 0 -scene_zone0_face z0/x>1 -scene_zone0_other_body 1 -scene_zone0_other_face z1"


def run(driver, options):
    cmd = shlex.split(driver) + shlex.split(options)
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines = [l for l in p.stdout.splitlines() if l.startswith('{"conefeti":')]
    if p.returncode != 0 or len(lines) != 1:
        print(p.stdout)
        sys.exit("symmetry-plane.py: %s exited with %d and %d JSON lines" % (" ".join(cmd), p.returncode, len(lines)))
    return json.loads(lines[0])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--driver", required=True)
    ap.add_argument("--half-driver")
    ap.add_argument("--meshes", required=True)
    ap.add_argument("--case", choices=["foundation", "bodies", "quarter"], required=True)
    ap.add_argument("--law", choices=["coulomb", "tresca"], required=True)
    ap.add_argument("--extra", default="")
    a = ap.parse_args()
    if a.case == "quarter":
        common = " ".join([BLOCK, laws(a.law, "1e7")])
        half = common + " -scene_name quarter " + QUARTER
        whole = common + " -scene_name whole -scene_body0_mesh %s/block-mirrored.msh -scene_body0_subdomains 8" % a.meshes
    else:
        common = " ".join([LOADS, zone(a.case), laws(a.law, "1.2e7")])
        half = common + " -scene_name half " + HALF_BRICK
        whole = common + " -scene_name whole -scene_body0_mesh %s/brick-mirrored.msh -scene_body0_subdomains 6" % a.meshes
    if a.case == "bodies":
        half += " " + HALF_SLAB
        whole += (" -scene_body1_mesh %s/slab-mirrored.msh -scene_body1_subdomains 3 -scene_body1_fix z0"
                  " -scene_body1_E 21.2e10 -scene_body1_nu 0.277" % a.meshes)
    h = run(a.half_driver or a.driver, half + " " + a.extra)
    w = run(a.driver, whole + " " + a.extra)
    failed = []

    share = 4 if a.case == "quarter" else 2

    def agree(what, hv, wv, scale):
        err = abs(share * hv - wv) / scale
        print("%-22s part x %d = %.9e  whole = %.9e  difference / scale %.2e" % (what, share, share * hv, wv, err))
        if not err <= 1e-5:
            failed.append(what)
    for d in (h, w):
        print("%s: converged %s, %d contact nodes (%d separated, %d stick, %d slip), left out %d, largest residual %.2e" %
              (d["scene"], d["converged"], d["contact_nodes"], d["separated"], d["stick"], d["slip"], d["left_out_friction"], d["residuals"]["max"]))
        if not d["converged"] or d["left_out_friction"]:
            failed.append(d["scene"] + ": not converged, or friction nodes left out")
    scale = abs(w["normal_force"])
    agree("sum of normal forces", h["normal_force"], w["normal_force"], scale)
    agree("contact force along z", h["contact_force"][2], w["contact_force"][2], scale)
    if a.case != "quarter":
        agree("contact force along x", h["contact_force"][0], w["contact_force"][0], scale)
    if a.case != "quarter" and w["contact_nodes"] != 2 * h["contact_nodes"] - PLANE_NODES:
        failed.append("contact nodes: whole %d, half %d (expected 2 half - %d)" % (w["contact_nodes"], h["contact_nodes"], PLANE_NODES))
    if not w["slip"] or not w["stick"]:
        failed.append("the whole model should have both stick and slip nodes")
    if a.case == "quarter" and not h["normal_force"] > 0:
        failed.append("the sphere presses on the quarter's symmetry planes only: no force")
    if failed:
        sys.exit("symmetry-plane.py: FAILED: " + "; ".join(failed))
    print("symmetry-plane.py: the %s model on rollers carries its share of the whole model's contact force" % ("quarter" if a.case == "quarter" else "half"))


main()
