/* The seed paper's brick: a steel brick (0,3)x(0,1)x(0,1), cut into three cubes, clamped on x = 0,
   pressed onto a rigid foundation and pulled sideways; Coulomb friction on the bottom of the two
   free cubes.

   Sample runs:
     brick -k 4 -friction 0.3                       (n = 900, the paper's smallest size)
     brick -k 12 -friction 0.1 -contact_coulomb_algorithm msa
     brick -k 4 -law frictionless                   (no tangential multipliers, mprgp only)
     brick -k 4 -paper_m -gap 3e-3                  (a contact strip of the paper's size, see below)
   Prints the pipeline, the counts of the paper's tables (n, m, Iter, n_A = QPP + QPQ + other: every Hessian
   product of the solve, where the conefeti driver's n_A leaves out the bonded start's, "other"), the node
   states and the mechanical residuals. Exit status: 0 when the solve converged, 2 when it did not
   (as the conefeti driver). */
#include <conefeti.h>

/* the bottom faces whose centroid lies in x in (xrange[0], xrange[1]) */
static PetscErrorCode ContactFace(const PetscReal c[3], const PetscReal n[3], PetscBool *tagged, void *ctx)
{
  const PetscReal *xrange = (const PetscReal *)ctx;
  *tagged                 = (c[0] > xrange[0] && c[0] < xrange[1] && n[2] < -0.5) ? PETSC_TRUE : PETSC_FALSE;
  return PETSC_SUCCESS;
}

int main(int argc, char **argv)
{
  FEM               fem;
  ContactModel      cm;
  ContactZone       zone = {};
  ContactStatistics st;
  ContactResiduals  r;
  PetscInt          k = 4, cells[3], sub[3] = {3, 1, 1}, b, n, m;
  PetscReal         lo[3] = {0, 0, 0}, hi[3] = {3, 1, 1}, friction = 0.3, p = 4e7, tau = 2e6, gap = 1e-3, tilt = 0;
  ContactLaw        law = CONTACT_COULOMB;
  Vec               lambda, u;
  PetscLogDouble    t0, t1, t2;
  PetscBool         converged, paperm = PETSC_FALSE, setfriction;
  PetscReal         xrange[2] = {1.0, 3.0}; /* the bottom of the two free cubes */

  PetscCall(PetscInitialize(&argc, &argv, NULL, "The paper's brick"));
  PetscCall(ConeFETIInitializePackage());
  /* the tutorial's own options, listed by -help and checked before anything is built */
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "The paper's brick", "brick");
  PetscCall(PetscOptionsBoundedInt("-k", "Cells per cube edge (n = 9k(k+1)^2)", "brick", k, &k, NULL, 1));
  PetscCall(PetscOptionsEnum("-law", "Contact law of the bottom", "brick", ContactLaws, (PetscEnum)law, (PetscEnum *)&law, NULL));
  PetscCall(PetscOptionsReal("-friction", "Coulomb coefficient F (with -law tresca: the slip bound)", "brick", friction, &friction, &setfriction));
  PetscCall(PetscOptionsReal("-pressure", "Pressure on the top face z = 1", "brick", p, &p, NULL));
  PetscCall(PetscOptionsReal("-shear", "Traction along x on the end face x = 3", "brick", tau, &tau, NULL));
  PetscCall(PetscOptionsReal("-gap", "Distance of the foundation below the bottom z = 0", "brick", gap, &gap, NULL));
  PetscCall(PetscOptionsReal("-tilt", "Slope of the foundation along x (the gap grows with x)", "brick", tilt, &tilt, NULL));
  /* The paper's m = 6(k+1)^2 gluing rows + 3 (k+1)(k-2) contact rows: its contact zone (Figure 1, lost)
     had k - 2 node columns across the full width. -paper_m takes the strip of the third cube from one
     cell after the interface to two cells before the end, x in [2 + 1/k, 3 - 2/k]: same n and m */
  PetscCall(PetscOptionsBool("-paper_m", "Contact on a strip of the third cube with the paper's m instead of the whole bottom of the free cubes", "brick", paperm, &paperm, NULL));
  PetscOptionsEnd();
  {
    const char     *name[]  = {"-pressure", "-shear", "-gap", "-tilt"};
    const PetscReal value[] = {p, tau, gap, tilt};
    for (int i = 0; i < 4; i++) PetscCheck(!PetscIsInfOrNanReal(value[i]), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "%s must be a finite number, got %g", name[i], (double)value[i]);
  }
  /* as the driver's scene: a frictionless law takes no -friction (it would be ignored silently) */
  PetscCheck(law != CONTACT_FRICTIONLESS || !setfriction, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-law frictionless takes no -friction (given %g): remove it or choose -law tresca or coulomb",
             (double)friction);
  PetscCheck(!PetscIsInfOrNanReal(friction) && friction >= 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-friction %g: the %s must be a finite number >= 0", (double)friction,
             law == CONTACT_TRESCA ? "slip bound" : "friction coefficient");
  if (paperm) {
    PetscCheck(k >= 4, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-paper_m needs -k >= 4 (the strip has k - 2 node columns), got -k %" PetscInt_FMT, k);
    xrange[0] = 2.0 + 1.0 / k; /* face centroids lie strictly inside their cells */
    xrange[1] = 3.0 - 2.0 / k;
  }
  PetscCall(PetscTime(&t0));
  cells[0] = 3 * k;
  cells[1] = cells[2] = k;
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddBox(fem, lo, hi, cells, &b));
  PetscCall(FEMSetMaterial(fem, b, 21.2e10, 0.277));
  PetscCall(FEMSetDirichlet(fem, b, "x0", NULL));
  {
    PetscReal top[3] = {0, 0, -p}, end[3] = {tau, 0, 0};
    PetscCall(FEMSetTraction(fem, b, "z1", top));
    PetscCall(FEMSetTraction(fem, b, "x1", end));
  }
  PetscCall(FEMTagFaces(fem, b, "contact", ContactFace, xrange));
  {
    PetscBool given; /* three cubes, as the paper, unless -fem_subdomains says otherwise */
    PetscCall(PetscOptionsHasName(NULL, NULL, "-fem_subdomains", &given));
    if (!given) PetscCall(FEMSetDecomposition(fem, b, FEM_DECOMPOSITION_STRUCTURED, sub));
  }
  PetscCall(FEMSetDirichletMode(fem, FEM_DIRICHLET_PRIMAL)); /* the paper: Gamma_u in the primal, 12 rigid modes */
  PetscCall(FEMSetFromOptions(fem));
  PetscCall(FEMSetUp(fem));

  PetscCall(ContactModelCreate(fem, &cm));
  zone.type = CONTACT_ZONE_FOUNDATION;
  zone.body = b;
  PetscCall(PetscStrcpy(zone.face, "contact"));
  zone.point[2]  = -gap;
  zone.normal[0] = tilt; /* a tilted plane: the gap grows along x */
  zone.normal[2] = 1;
  zone.law       = law;
  zone.coef      = friction;
  PetscCall(ContactModelAddZone(cm, &zone));
  PetscCall(ContactModelSetUp(cm));
  PetscCall(PetscTime(&t1));
  PetscCall(ContactModelSolve(cm));
  PetscCall(PetscTime(&t2));
  PetscCall(ContactModelGetStatistics(cm, &st));
  PetscCall(ContactModelComputeResiduals(cm, &r));
  PetscCall(ContactModelGetSolution(cm, &lambda, &u));
  PetscCall(VecGetSize(lambda, &m));
  n = 3 * 3 * k * (k + 1) * (k + 1); /* unknowns of the undecomposed mesh without the clamped face */
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "pipeline %s; %s\n", ContactPipelines[st.pipeline], st.reason));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "n %" PetscInt_FMT " m %" PetscInt_FMT " Iter %" PetscInt_FMT " n_A %" PetscInt_FMT " (QPP %" PetscInt_FMT " + QPQ %" PetscInt_FMT " + other %" PetscInt_FMT
                        ") estimate %" PetscInt_FMT " setup %.3f s solve %.3f s\n",
                        n, m, st.outer_iterations, st.products_qpp + st.products_qpq + st.products_other, st.products_qpp, st.products_qpq, st.products_other, st.products_estimate, t1 - t0, t2 - t1));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "nodes: %" PetscInt_FMT " separated, %" PetscInt_FMT " stick, %" PetscInt_FMT " slip\n", r.counts[0], r.counts[1], r.counts[2]));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "residuals: equilibrium %.1e gluing %.1e penetration %.1e sign %.1e complementarity %.1e cone %.1e slip %.1e\n", (double)r.equilibrium, (double)r.gluing,
                        (double)r.penetration, (double)r.normal_sign, (double)r.complementarity, (double)r.friction_cone, (double)r.slip_rule));
  converged = st.converged;
  PetscCall(ContactModelDestroy(&cm));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscFinalize());
  return converged ? 0 : 2;
}
