/* ContactProblem: a dual contact problem (operator, right-hand side, equality, contact nodes). */
#include <conefeti/private/contactimpl.h>
#include <conefeti/sys.h>

PetscClassId      CONTACTPROBLEM_CLASSID;
const char *const ContactLaws[]              = {"frictionless", "tresca", "coulomb", "ContactLaw", "CONTACT_", NULL};
const char *const ContactPipelines[]         = {"linear", "frictionless", "tresca", "coulomb", "ContactPipeline", "CONTACT_PIPELINE_", NULL};
const char *const ContactCoulombAlgorithms[] = {"msa", "merged", "monolithic", "ContactCoulombAlgorithm", "CONTACT_COULOMB_", NULL};

/*@C
  ContactProblemCreate - Create an empty dual contact problem.

  Collective

  Input Parameter:
. comm - the communicator

  Output Parameter:
. cp - the problem

  Level: beginner

.seealso: `ContactProblemSetOperator()`, `ContactProblemAddNodes()`, `ContactProblemSolve()`
@*/
PetscErrorCode ContactProblemCreate(MPI_Comm comm, ContactProblem *cp)
{
  ContactProblem c;

  PetscFunctionBegin;
  PetscAssertPointer(cp, 2);
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscHeaderCreate(c, CONTACTPROBLEM_CLASSID, "ContactProblem", "Dual contact problem", "Contact", comm, ContactProblemDestroy, ContactProblemView));
  PetscCallCXX(c->data = new ContactProblemData);
  *cp = c;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemDestroy - Destroy a contact problem.

  Collective

  Input Parameter:
. cp - the problem

  Level: beginner

.seealso: `ContactProblemCreate()`
@*/
PetscErrorCode ContactProblemDestroy(ContactProblem *cp)
{
  ContactProblemData *d;

  PetscFunctionBegin;
  if (!*cp) PetscFunctionReturn(PETSC_SUCCESS);
  PetscValidHeaderSpecific(*cp, CONTACTPROBLEM_CLASSID, 1);
  if (--((PetscObject)(*cp))->refct > 0) {
    *cp = NULL;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  d = (*cp)->data;
  PetscCall(MatDestroy(&d->F));
  PetscCall(VecDestroy(&d->h));
  PetscCall(MatDestroy(&d->G));
  PetscCall(VecDestroy(&d->e));
  PetscCall(MatDestroy(&d->Q));
  PetscCall(VecDestroy(&d->lt));
  PetscCall(SeparableSetDestroy(&d->set));
  PetscCall(VecDestroy(&d->lb));
  PetscCall(VecDestroy(&d->ub));
  PetscCall(TaoDestroy(&d->tao));
  PetscCall(PCDestroy(&d->pc));
  PetscCall(MatDestroy(&d->C0));
  PetscCall(VecDestroy(&d->d0));
  delete d;
  PetscCall(PetscHeaderDestroy(cp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Replace(PetscObject src, PetscObject *dst)
{
  PetscFunctionBegin;
  if (src) PetscCall(PetscObjectReference(src));
  PetscCall(PetscObjectDestroy(dst));
  *dst = src;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckNotSetUp(ContactProblem cp, const char *what)
{
  PetscFunctionBegin;
  PetscCheck(!cp->data->setup, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_WRONGSTATE, "ContactProblem: %s must be given before the first solve", what);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemSetOperator - The quadratic part: F (symmetric positive semidefinite, any Mat with
  MatMult, e.g. FETI's MATSHELL B K+ B') and the right-hand side h.

  Logically Collective

  Input Parameters:
+ cp - the problem
. F  - the operator
- h  - the linear term (minimize 1/2 l'Fl - l'h)

  Level: beginner

.seealso: `ContactProblemSetProjector()`, `ContactProblemSetEquality()`
@*/
PetscErrorCode ContactProblemSetOperator(ContactProblem cp, Mat F, Vec h)
{
  PetscInt m, n, N;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  /* PetscValidHeaderSpecific() checks nothing in a PETSc built without debugging (the packaged one) */
  PetscCheck(F && h, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_NULL, "ContactProblemSetOperator: give both F and h (%s is NULL)", F ? "h" : "F");
  PetscValidHeaderSpecific(F, MAT_CLASSID, 2);
  PetscValidHeaderSpecific(h, VEC_CLASSID, 3);
  PetscCall(CheckNotSetUp(cp, "the operator"));
  PetscCall(MatGetSize(F, &m, &n));
  PetscCall(VecGetSize(h, &N));
  PetscCheck(m == n && n == N, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_SIZ, "ContactProblemSetOperator: F is %" PetscInt_FMT " x %" PetscInt_FMT ", h has %" PetscInt_FMT " entries", m, n, N);
  PetscCall(Replace((PetscObject)F, (PetscObject *)&cp->data->F));
  PetscCall(Replace((PetscObject)h, (PetscObject *)&cp->data->h));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemSetEquality - An equality G l = e (full row rank); the solver uses the penalty form
  of the augmented Lagrangian.

  Logically Collective

  Input Parameters:
+ cp - the problem
. G  - the constraint matrix
- e  - the right-hand side

  Level: intermediate

.seealso: `ContactProblemSetProjector()`
@*/
PetscErrorCode ContactProblemSetEquality(ContactProblem cp, Mat G, Vec e)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscCheck(G && e, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_NULL, "ContactProblemSetEquality: give both G and e (%s is NULL)", G ? "e" : "G");
  PetscValidHeaderSpecific(G, MAT_CLASSID, 2);
  PetscValidHeaderSpecific(e, VEC_CLASSID, 3);
  PetscCall(CheckNotSetUp(cp, "the equality"));
  {
    PetscInt m, N;
    PetscCall(MatGetSize(G, &m, NULL));
    PetscCall(VecGetSize(e, &N));
    PetscCheck(m == N, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_SIZ, "ContactProblemSetEquality: G has %" PetscInt_FMT " rows, e has %" PetscInt_FMT " entries", m, N);
  }
  PetscCall(Replace((PetscObject)G, (PetscObject *)&cp->data->G));
  PetscCall(Replace((PetscObject)e, (PetscObject *)&cp->data->e));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemSetProjector - The equality in projector form: Q the orthogonal projector onto the
  range of G' and lt a particular solution (G lt = e). FETI provides both (`FETIGetOperators()`,
  `FETIGetParticularSolution()`); the inner Hessian is then PFP + rho Q.

  Logically Collective

  Input Parameters:
+ cp - the problem
. Q  - the projector
- lt - the particular solution

  Level: beginner

.seealso: `ContactProblemSetEquality()`, `TaoSMALXESetProjector()`
@*/
PetscErrorCode ContactProblemSetProjector(ContactProblem cp, Mat Q, Vec lt)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  /* a NULL Q dropped the equality without a word and the solve reported converged; a NULL lt crashed */
  PetscCheck(Q && lt, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_NULL, "ContactProblemSetProjector: give both Q and lt (%s is NULL; for e = 0 give a zero vector)", Q ? "lt" : "Q");
  PetscValidHeaderSpecific(Q, MAT_CLASSID, 2);
  PetscValidHeaderSpecific(lt, VEC_CLASSID, 3);
  PetscCall(CheckNotSetUp(cp, "the projector"));
  PetscCall(Replace((PetscObject)Q, (PetscObject *)&cp->data->Q));
  PetscCall(Replace((PetscObject)lt, (PetscObject *)&cp->data->lt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemAddNodes - Add contact nodes of one law, owned by this rank.

  Not Collective

  Input Parameters:
+ cp     - the problem
. law    - `CONTACT_FRICTIONLESS`, `CONTACT_TRESCA` or `CONTACT_COULOMB`
. n      - number of nodes
. normal - global index of each node's normal multiplier (constrained to >= 0)
. t1     - global index of each node's first tangential multiplier (NULL when frictionless)
. t2     - global index of the second tangential multiplier (NULL when frictionless)
- coef   - Tresca: slip bound g_k >= 0 (in multiplier units); Coulomb: coefficient F_k >= 0; NULL when frictionless

  Notes:
  The three multipliers of a node must be owned by this rank (a block never straddles ranks).
  Frictionless nodes have no tangential multipliers at all: a frictionless scene creates none.
  The solvers hold a slip bound (g_k, or F_k l_n) below 1e150, where it acts as an infinite one: they square the
  bounds, and a bound near the largest real would overflow to NaN instead of sticking.

  Level: beginner

.seealso: `ContactLaw`, `ContactProblemSolve()`
@*/
PetscErrorCode ContactProblemAddNodes(ContactProblem cp, ContactLaw law, PetscInt n, const PetscInt normal[], const PetscInt t1[], const PetscInt t2[], const PetscReal coef[])
{
  ContactProblemData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscCall(CheckNotSetUp(cp, "contact nodes"));
  d = cp->data;
  PetscCheck(n >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "ContactProblemAddNodes: negative count %" PetscInt_FMT, n);
  PetscCheck(law == CONTACT_FRICTIONLESS || law == CONTACT_TRESCA || law == CONTACT_COULOMB, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "ContactProblemAddNodes: %d is no ContactLaw", (int)law);
  PetscCheck(normal || n == 0, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "ContactProblemAddNodes: %" PetscInt_FMT " nodes need their normal multiplier indices (normal is NULL)", n);
  PetscCheck(law == CONTACT_FRICTIONLESS || (t1 && t2 && coef) || n == 0, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "ContactProblemAddNodes: %s nodes need t1, t2 and coefficients", ContactLaws[law]);
  PetscCheck(law == CONTACT_FRICTIONLESS || !d->polygon || n == 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
             "ContactProblemAddNodes: the problem has friction polygons (ContactProblemAddPolygonNodes()); its %s nodes cannot have disks too", ContactLaws[law]);
  for (PetscInt k = 0; k < n; k++) {
    PetscReal c = law == CONTACT_FRICTIONLESS ? 0.0 : coef[k];
    PetscCheck(c >= 0 && !PetscIsInfOrNanReal(c), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "ContactProblemAddNodes: node %" PetscInt_FMT " has invalid %s %g (must be finite and >= 0)", k,
               law == CONTACT_TRESCA ? "slip bound" : "friction coefficient", (double)c);
    PetscCallCXX(d->normal.push_back(normal[k]));
    PetscCallCXX(d->t1.push_back(law == CONTACT_FRICTIONLESS ? -1 : t1[k]));
    PetscCallCXX(d->t2.push_back(law == CONTACT_FRICTIONLESS ? -1 : t2[k]));
    PetscCallCXX(d->law.push_back(law));
    PetscCallCXX(d->coef.push_back(c));
    if (d->polygon) PetscCallCXX(d->tang.insert(d->tang.end(), d->polygon, -1));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemAddPolygonNodes - Add contact nodes of one law, owned by this rank, whose friction disk is replaced by
  a polygon expressed through simple bounds only (the approximate method the seed paper compares with in its Table 3).

  Not Collective

  Input Parameters:
+ cp         - the problem
. law        - `CONTACT_TRESCA` or `CONTACT_COULOMB` (`CONTACT_FRICTIONLESS` nodes have no tangential multipliers: use
               `ContactProblemAddNodes()`)
. n          - number of nodes
. k          - tangential multipliers per node (k >= 2, the same for every polygon node of the problem)
. normal     - global index of each node's normal multiplier (constrained to >= 0)
. tangential - k global indices per node: the multipliers of the rows along d_j = cos(j pi/k) t1 + sin(j pi/k) t2, j = 0..k-1
- coef       - Tresca: slip bound g_k >= 0; Coulomb: coefficient F_k >= 0 (g_k = F_k max(l_n, 0))

  Notes:
  Each tangential multiplier is bounded by |m_j| <= sin(pi/(2k)) g: the tangential force sum_j m_j d_j then ranges
  over a regular 2k-gon inscribed in the disk of radius g (a square for k = 2, an octagon for k = 4), and the
  dual problem has bounds only, solved by mprgp. A problem's friction nodes are all disks or all polygons.
  The slip bounds (`ContactProblemGetSlipBounds()`) stay g: the radius of the disk the polygon approximates.

  Level: intermediate

.seealso: `ContactProblemAddNodes()`, `ContactProblemGetFrictionPolygon()`
@*/
PetscErrorCode ContactProblemAddPolygonNodes(ContactProblem cp, ContactLaw law, PetscInt n, PetscInt k, const PetscInt normal[], const PetscInt tangential[], const PetscReal coef[])
{
  ContactProblemData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscCall(CheckNotSetUp(cp, "contact nodes"));
  d = cp->data;
  PetscCheck(n >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "ContactProblemAddPolygonNodes: negative count %" PetscInt_FMT, n);
  PetscCheck(law == CONTACT_FRICTIONLESS || law == CONTACT_TRESCA || law == CONTACT_COULOMB, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "ContactProblemAddPolygonNodes: %d is no ContactLaw", (int)law);
  PetscCheck(law != CONTACT_FRICTIONLESS, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "ContactProblemAddPolygonNodes: frictionless nodes have no friction polygon (ContactProblemAddNodes())");
  PetscCheck(k >= 2, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "ContactProblemAddPolygonNodes: a friction polygon needs k >= 2 directions, got %" PetscInt_FMT, k);
  PetscCheck(!d->polygon || d->polygon == k, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "ContactProblemAddPolygonNodes: the problem's polygons have %" PetscInt_FMT " directions, not %" PetscInt_FMT,
             d->polygon, k);
  if (n == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(normal && tangential && coef, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "ContactProblemAddPolygonNodes: %s nodes need normal and tangential indices and coefficients", ContactLaws[law]);
  for (ContactLaw l : d->law)
    PetscCheck(l == CONTACT_FRICTIONLESS || d->polygon, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
               "ContactProblemAddPolygonNodes: the problem has friction disks (ContactProblemAddNodes()); its nodes cannot have polygons too");
  if (!d->polygon) PetscCallCXX(d->tang.assign(d->normal.size() * k, -1)); /* the frictionless nodes added so far */
  d->polygon = k;
  for (PetscInt i = 0; i < n; i++) {
    PetscCheck(coef[i] >= 0 && !PetscIsInfOrNanReal(coef[i]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "ContactProblemAddPolygonNodes: node %" PetscInt_FMT " has invalid %s %g (must be finite and >= 0)", i, law == CONTACT_TRESCA ? "slip bound" : "friction coefficient", (double)coef[i]);
    PetscCallCXX(d->normal.push_back(normal[i]));
    PetscCallCXX(d->t1.push_back(-1));
    PetscCallCXX(d->t2.push_back(-1));
    PetscCallCXX(d->law.push_back(law));
    PetscCallCXX(d->coef.push_back(coef[i]));
    PetscCallCXX(d->tang.insert(d->tang.end(), tangential + i * k, tangential + (i + 1) * k));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemGetFrictionPolygon - The friction polygon of the problem's nodes, if they have one.

  Not Collective

  Input Parameter:
. cp - the problem

  Output Parameters:
+ k          - tangential multipliers per friction node (0: friction disks, `ContactProblemAddNodes()`)
- tangential - k global indices per local node, in the order of `ContactProblemGetNodes()` (-1 for frictionless nodes), or NULL

  Level: intermediate

.seealso: `ContactProblemAddPolygonNodes()`
@*/
PetscErrorCode ContactProblemGetFrictionPolygon(ContactProblem cp, PetscInt *k, const PetscInt **tangential)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  if (k) *k = cp->data->polygon;
  if (tangential) *tangential = cp->data->polygon ? cp->data->tang.data() : NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemGetNodes - The contact nodes of this rank.

  Not Collective

  Input Parameter:
. cp - the problem

  Output Parameters:
+ n      - number of local nodes
. normal - global indices of the normal multipliers
. t1     - first tangential multipliers (-1 for frictionless nodes and polygon nodes: `ContactProblemGetFrictionPolygon()`)
. t2     - second tangential multipliers (-1 for frictionless nodes)
. law    - law per node
- coef   - slip bound (Tresca) or coefficient (Coulomb) per node

  Level: intermediate

.seealso: `ContactProblemAddNodes()`
@*/
PetscErrorCode ContactProblemGetNodes(ContactProblem cp, PetscInt *n, const PetscInt **normal, const PetscInt **t1, const PetscInt **t2, const ContactLaw **law, const PetscReal **coef)
{
  ContactProblemData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  d = cp->data;
  if (n) *n = (PetscInt)d->normal.size();
  if (normal) *normal = d->normal.data();
  if (t1) *t1 = d->t1.data();
  if (t2) *t2 = d->t2.data();
  if (law) *law = d->law.data();
  if (coef) *coef = d->coef.data();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemSetOptionsPrefix - Prefix for the options of the problem and its solvers.

  Logically Collective

  Input Parameters:
+ cp     - the problem
- prefix - the prefix (options become -<prefix>contact_...)

  Level: intermediate

.seealso: `ContactProblemSetFromOptions()`
@*/
PetscErrorCode ContactProblemSetOptionsPrefix(ContactProblem cp, const char prefix[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)cp, prefix));
  if (cp->data->pc) { /* the preconditioner's (ContactProblemGetPC()) follows */
    PetscCall(PCSetOptionsPrefix(cp->data->pc, prefix));
    PetscCall(PCAppendOptionsPrefix(cp->data->pc, "contact_"));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemGetPipeline - The pipeline the problem calls for (valid after `ContactProblemSetUp()`).

  Not Collective

  Input Parameter:
. cp - the problem

  Output Parameter:
. pipeline - linear, frictionless, tresca or coulomb

  Level: beginner

.seealso: `ContactPipeline`
@*/
PetscErrorCode ContactProblemGetPipeline(ContactProblem cp, ContactPipeline *pipeline)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscCheck(cp->data->setup, PETSC_COMM_SELF, PETSC_ERR_ORDER, "ContactProblemGetPipeline: call ContactProblemSetUp() first (it chooses the pipeline)");
  *pipeline = cp->data->pipeline;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemGetStatistics - Iterations, Hessian products and how the last solve ended.

  Not Collective

  Input Parameter:
. cp - the problem

  Output Parameter:
. stats - the statistics

  Level: beginner

.seealso: `ContactStatistics`
@*/
PetscErrorCode ContactProblemGetStatistics(ContactProblem cp, ContactStatistics *stats)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  *stats = cp->data->stats;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemSetProgress - A hook told of every outer iteration of `ContactProblemSolve()` (the augmented
  Lagrangian's, within each successive approximation for MSA): the largest residual on the scale of the
  solver's relative tolerance, and that tolerance.

  Logically Collective

  Input Parameters:
+ cp  - the problem
. fn  - the hook (NULL: none)
- ctx - its context

  Notes:
  The reports have the phase `CONEFETI_PHASE_SOLVE` and never `done`: whoever runs the solve reports its
  beginning and end (`ContactModelSolve()`). The hook is a `TaoMonitor` on the problem's solver, installed at the
  first solve. A `ContactModel` passes its own hook on (`ContactModelSetProgress()`).

  Level: intermediate

.seealso: `ConeFETIProgressFn`, `ContactModelSetProgress()`, `TaoSMALXEGetOuterTolerances()`
@*/
PetscErrorCode ContactProblemSetProgress(ContactProblem cp, ConeFETIProgressFn fn, void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  cp->data->progress.fn  = fn;
  cp->data->progress.ctx = ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemGetTao - The smalxe solver the contact solve uses (after `ContactProblemSetUp()`).

  Not Collective

  Input Parameter:
. cp - the problem

  Output Parameter:
. tao - the solver (options prefix -contact_)

  Level: advanced

.seealso: `TAOSMALXE`
@*/
PetscErrorCode ContactProblemGetTao(ContactProblem cp, Tao *tao)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscCheck(cp->data->setup, PETSC_COMM_SELF, PETSC_ERR_ORDER, "ContactProblemGetTao: call ContactProblemSetUp() first (it creates the solver)");
  *tao = cp->data->tao;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemGetSlipBounds - The slip bound of every local contact node for given multipliers:
  the given bound (Tresca), F_k max(l_n,k, 0) (Coulomb), 0 (frictionless).

  Not Collective

  Input Parameters:
+ cp     - the problem
- lambda - the multipliers

  Output Parameter:
. bounds - one value per local node, in the order of `ContactProblemGetNodes()`

  Level: intermediate

.seealso: `ContactProblemGetNodes()`
@*/
PetscErrorCode ContactProblemGetSlipBounds(ContactProblem cp, Vec lambda, PetscReal bounds[])
{
  ContactProblemData *d;
  const PetscScalar  *l;
  PetscInt            rstart, rend;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscCheck(lambda, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "ContactProblemGetSlipBounds: lambda is NULL");
  PetscValidHeaderSpecific(lambda, VEC_CLASSID, 2);
  d = cp->data;
  PetscCheck(d->h, PETSC_COMM_SELF, PETSC_ERR_ORDER, "ContactProblemGetSlipBounds: call ContactProblemSetOperator() first");
  {
    PetscInt n, N, hn, hN;
    PetscCall(VecGetLocalSize(lambda, &n));
    PetscCall(VecGetSize(lambda, &N));
    PetscCall(VecGetLocalSize(d->h, &hn));
    PetscCall(VecGetSize(d->h, &hN));
    PetscCheck(n == hn && N == hN, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "ContactProblemGetSlipBounds: lambda has %" PetscInt_FMT " entries (%" PetscInt_FMT " on this rank), the multipliers %" PetscInt_FMT " (%" PetscInt_FMT ")", N, n, hN, hn);
  }
  PetscCall(VecGetOwnershipRange(lambda, &rstart, &rend));
  PetscCall(VecGetArrayRead(lambda, &l));
  for (size_t k = 0; k < d->normal.size(); k++) {
    /* before the setup has validated the nodes, an index off this rank would read past the array */
    PetscCheck(d->law[k] != CONTACT_COULOMB || (d->normal[k] >= rstart && d->normal[k] < rend), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "ContactProblemGetSlipBounds: node %zu's normal multiplier %" PetscInt_FMT " is not owned by this rank (rows %" PetscInt_FMT " to %" PetscInt_FMT ")", k, d->normal[k], rstart,
               rend - 1);
    switch (d->law[k]) {
    case CONTACT_FRICTIONLESS: bounds[k] = 0; break;
    case CONTACT_TRESCA: bounds[k] = d->coef[k]; break;
    case CONTACT_COULOMB: bounds[k] = d->coef[k] * PetscMax(PetscRealPart(l[d->normal[k] - rstart]), 0.0); break;
    }
  }
  PetscCall(VecRestoreArrayRead(lambda, &l));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemView - Describe the problem: sizes, nodes per law, pipeline, last solve.

  Collective

  Input Parameters:
+ cp     - the problem
- viewer - an ASCII viewer (or NULL)

  Level: beginner

.seealso: `ContactProblemSolve()`
@*/
PetscErrorCode ContactProblemView(ContactProblem cp, PetscViewer viewer)
{
  ContactProblemData *d;
  PetscInt            counts[3] = {0, 0, 0}, m = 0;
  PetscBool           iascii;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  d = cp->data;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(PetscObjectComm((PetscObject)cp), &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(PETSC_SUCCESS);
  for (ContactLaw l : d->law) counts[l]++;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 3, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)cp)));
  if (d->h) PetscCall(VecGetSize(d->h, &m));
  PetscCall(PetscObjectPrintClassNamePrefixType((PetscObject)cp, viewer));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%" PetscInt_FMT " multipliers; contact nodes: %" PetscInt_FMT " frictionless, %" PetscInt_FMT " Tresca, %" PetscInt_FMT " Coulomb; equality: %s\n", m,
                                   counts[0], counts[1], counts[2], d->Q ? "projector form" : (d->G ? "penalty form" : "none")));
  PetscCall(PetscViewerASCIIPrintf(viewer, "pipeline: %s%s%s\n", ContactPipelines[d->pipeline], d->pipeline == CONTACT_PIPELINE_COULOMB ? ", algorithm " : "",
                                   d->pipeline == CONTACT_PIPELINE_COULOMB ? ContactCoulombAlgorithms[d->algorithm] : ""));
  if (d->polygon)
    PetscCall(PetscViewerASCIIPrintf(viewer, "friction polygons: %" PetscInt_FMT " bounded tangential multipliers per node, a regular %" PetscInt_FMT "-gon inscribed in each friction disk\n",
                                     d->polygon, 2 * d->polygon));
  if (d->stats.outer_iterations)
    PetscCall(PetscViewerASCIIPrintf(
        viewer, "last solve: %s; Iter %" PetscInt_FMT ", n_A = %" PetscInt_FMT " (QPP %" PetscInt_FMT " + QPQ %" PetscInt_FMT " + other %" PetscInt_FMT "), norm estimate %" PetscInt_FMT "\n",
        d->stats.reason, d->stats.outer_iterations, d->stats.products_qpp + d->stats.products_qpq + d->stats.products_other, d->stats.products_qpp, d->stats.products_qpq, d->stats.products_other,
        d->stats.products_estimate));
  if (d->tao) PetscCall(TaoView(d->tao, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemGetCoulombAlgorithm - The algorithm of the Coulomb friction loop (set by `-contact_coulomb_algorithm`).

  Not Collective

  Input Parameter:
. cp - the problem

  Output Parameter:
. algorithm - msa, merged or monolithic (meaningful for the Coulomb pipeline)

  Level: intermediate

.seealso: `ContactCoulombAlgorithm`, `ContactProblemGetPipeline()`
@*/
PetscErrorCode ContactProblemGetCoulombAlgorithm(ContactProblem cp, ContactCoulombAlgorithm *algorithm)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  *algorithm = cp->data->algorithm;
  PetscFunctionReturn(PETSC_SUCCESS);
}
