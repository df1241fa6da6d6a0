/* The starting multipliers of a cold contact solve: the particular solution of G l = e, or that improved by a few
   projected CG steps on the dual problem without its inequalities (every contact node held bonded: normal and
   tangential multipliers free).

   Why: the particular solution l~ = G'(GG')^-1 e spreads the rigid-body loads over all multipliers; its normal
   contact multipliers are no contact pressure. The first inner solve then finds the active set from it by
   expansion steps of fixed length, whose number grows with the width of the contact zone in nodes, and with
   Coulomb friction the first radii F l_n come from l~ and move by 40-70% after the first solve (docs/scale.md,
   "Why n_A grows: the outer loop"). The bonded problem is linear and FETI-scalable: a loose CG on it gives
   normal multipliers that are a contact pressure where the bodies press, negative where they would separate
   (the inner solver's projection sets those to 0), and tangential ones that the projection onto the disks of
   radius F max(l_n, 0) cuts to slip. On curved contacts (a sphere on a plane) the bonded zone reaches far beyond the
   contact and most of its normal force is tension; started from there the brick's gain turns into a loss (up to
   +64% products on the hemisphere), so the start is abandoned when too little of it presses
   (-contact_start_compressive). Measurements: docs/scale.md, "Lever: a bonded start". */
#include <conefeti/private/contactimpl.h>
#include <conefeti/private/fetiimpl.h>
#include <conefeti/private/operatortest.h>
#include <conefeti/private/reproduciblesum.h>

namespace {

/* y = P x = x - Q x */
PetscErrorCode Project(Mat Q, Vec x, Vec y, Vec work)
{
  PetscFunctionBegin;
  PetscCall(MatMult(Q, x, work));
  PetscCall(VecWAXPY(y, -1.0, work, x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One CG step of the two starts, given w = A p (A the projected operator): x += alpha p, r -= alpha w, p = r + beta p,
   rr = |r|^2; stepped is false (and nothing changes) when p'w <= 0, where A is semidefinite only up to rounding */
PetscErrorCode CGStep(Vec x, Vec r, Vec p, Vec w, PetscReal *rr, PetscBool *stepped)
{
  PetscReal pw, rrnew;

  PetscFunctionBegin;
  PetscCall(ReproducibleDot(p, w, &pw));
  *stepped = pw > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (!*stepped) PetscFunctionReturn(PETSC_SUCCESS);
  const PetscReal alpha = *rr / pw;
  PetscCall(ReproducibleAXPY(x, alpha, p));
  PetscCall(ReproducibleAXPY(r, -alpha, w));
  PetscCall(ReproducibleDot(r, r, &rrnew));
  PetscCall(ReproducibleAYPX(p, rrnew / *rr, r));
  *rr = rrnew;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the share of the normal multipliers' total |l_n| that is compressive (l_n > 0); 1 without normal multipliers */
PetscErrorCode CompressiveShare(ContactProblem cp, Vec lambda, PetscReal *share)
{
  ContactProblemData *d = cp->data;
  const PetscScalar  *l;
  PetscReal           sums[2] = {0, 0};

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(lambda, &l));
  for (size_t j = 0; j < d->normal.size(); j++) {
    const PetscReal v = PetscRealPart(l[d->normal[j] - d->rstart]);
    sums[0] += PetscMax(v, 0.0);
    sums[1] += PetscAbsReal(v);
  }
  PetscCall(VecRestoreArrayRead(lambda, &l));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 2, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)cp)));
  *share = sums[1] > 0 ? sums[0] / sums[1] : 1.0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The separated start: the solution with every contact row left out (its multipliers 0), when that solution touches
   nothing. Where the loads close no contact zone it is the answer, but the augmented Lagrangian finds it slowly: the
   normal multipliers sit at their bound 0 in every face, so G l = e rests on the gluing rows alone while the penalty
   acts through all of G's rows (docs/contact.md, "Zones that stay open"). Here G l = e is met on the gluing rows
   directly: with D the mask of the rows that are no contact rows and S = G D G' (factored once, as G G' is),
   l = l~_D + y, l~_D = D G'S^-1 e, y by CG on P_D D F D P_D, P_D = I - D G'S^-1 G D. With w = F l - h and
   a = S^-1 G D w, the gap of the primal solution at the rows is w - G'a (0 on the gluing rows, >= 0 on a normal
   row that touches nothing). When every normal gap is >= 0, l is the solution of the whole problem, and nu = Q(w - G'a)
   is the multiplier of its equality in smalxe's projector form (the projected gradient P(F l - h) + nu is then the
   gap itself: 0 on the free rows, >= 0 on the normal ones at their bound): the solve starts from both and its first
   outer iteration confirms them. Otherwise nothing changes. Frictionless and Coulomb rows only (a Tresca disk does
   not shrink to 0 away from contact). Returns the products with F it took. */
PetscErrorCode SeparatedStart(ContactProblem cp, Vec lambda, PetscBool *found, PetscInt *products)
{
  ContactProblemData *d = cp->data;
  FETI                feti;
  FETICoarseSolver    cs;
  Mat                 S = nullptr;
  Vec                 D = nullptr, l = nullptr, r = nullptr, p = nullptr, w = nullptr, t = nullptr, c1 = nullptr, c2 = nullptr, h, e;
  PetscBool           failed = PETSC_TRUE;
  PetscReal           rr = 0, rr0 = 0, mingap = 0, resid = 0;
  PetscBool           stepped;
  PetscInt            its = 0;

  PetscFunctionBegin;
  *found    = PETSC_FALSE;
  *products = 0;
  PetscCall(FETIFromMat(d->F, &feti));
  if (!feti || d->has_tresca) PetscFunctionReturn(PETSC_SUCCESS);
  {
    PetscInt ncoarse;
    PetscCall(FETIGetSizes(feti, NULL, NULL, &ncoarse));
    if (!ncoarse) PetscFunctionReturn(PETSC_SUCCESS); /* no floating subdomain: no equality for the gluing rows to carry */
  }
  { /* a node that starts inside its obstacle (gap c < 0) is pushed out by contact, unless the loads alone move it out: not
       worth a solve (on random indentations the start was dropped after up to 130 products) */
    Vec                c;
    const PetscScalar *ca;
    PetscReal          minc = PETSC_MAX_REAL;
    PetscCall(FETIGetConstraints(feti, NULL, &c, NULL));
    PetscCall(VecGetArrayRead(c, &ca));
    for (PetscInt row : d->normal) minc = PetscMin(minc, PetscRealPart(ca[row - d->rstart]));
    PetscCall(VecRestoreArrayRead(c, &ca));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &minc, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)cp)));
    if (minc < 0) {
      PetscCall(PetscInfo(cp, "Separated start: a contact node starts inside its obstacle (gap %g): not tried\n", (double)minc));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  PetscCall(FETIGetRHS(feti, &h, &e));
  PetscCall(VecDuplicate(lambda, &D));
  PetscCall(VecSet(D, 1.0));
  {
    PetscScalar *m;
    PetscCall(VecGetArray(D, &m));
    for (const std::vector<PetscInt> *rows : {&d->normal, &d->t1, &d->t2, &d->tang})
      for (PetscInt row : *rows)
        if (row >= 0) m[row - d->rstart] = 0;
    PetscCall(VecRestoreArray(D, &m));
  }
  PetscCall(FETICreateCoarseMatrix(feti, D, &S));
  PetscCall(FETICoarseSolverCreate(feti, S, cs, &failed));
  PetscCall(MatDestroy(&S));
  if (failed) { /* the gluing rows alone do not hold every body: contact is what holds it */
    PetscCall(PetscInfo(cp, "Separated start: G D G' is singular (the supports do not hold every body without contact): not tried\n"));
    goto done;
  }
  for (Vec *v : {&l, &r, &p, &w, &t}) PetscCall(VecDuplicate(lambda, v));
  PetscCall(VecDuplicate(e, &c1));
  PetscCall(VecDuplicate(e, &c2));
  {
    /* y = G'S^-1 b (c2 holds S^-1 b) */
    auto lift = [&](Vec b, Vec y) -> PetscErrorCode {
      PetscFunctionBegin;
      PetscCall(FETICoarseSolverApply(cs, b, c2));
      PetscCall(FETIApplyGt(feti, c2, y));
      PetscFunctionReturn(PETSC_SUCCESS);
    };
    /* y = D G'S^-1 b and |G y - b| / |b|: how well S's factors solve for b */
    auto solves = [&](Vec b, Vec y, PetscReal *rel) -> PetscErrorCode {
      PetscReal bn;
      PetscFunctionBegin;
      PetscCall(lift(b, y));
      PetscCall(VecPointwiseMult(y, D, y));
      PetscCall(FETIApplyG(feti, y, c2));
      PetscCall(VecAXPY(c2, -1.0, b));
      PetscCall(VecNorm(c2, NORM_2, rel));
      PetscCall(VecNorm(b, NORM_2, &bn));
      *rel = bn > 0 ? *rel / bn : 0;
      PetscFunctionReturn(PETSC_SUCCESS);
    };
    /* a singular S that rounding let through does not solve for b = G D v, v pseudo-random (the residual is then of the
       order of b, docs/feti.md); then l~_D = D G'S^-1 e, which must meet e */
    PetscCall(FETISetPseudoRandom_Private(r));
    PetscCall(VecPointwiseMult(r, D, r));
    PetscCall(FETIApplyG(feti, r, c1));
    PetscCall(solves(c1, r, &resid));
    if (!(resid <= 1e-8)) {
      PetscCall(PetscInfo(cp, "Separated start: G D G' solves only to %g (singular: the supports do not hold every body without contact): not tried\n", (double)resid));
      goto done;
    }
    PetscCall(solves(e, l, &resid));
    if (!(resid <= 1e-8)) {
      PetscCall(PetscInfo(cp, "Separated start: l~_D meets G D l = e only to %g: not tried\n", (double)resid));
      goto done;
    }
    /* y = P_D x (x masked): x - D G'S^-1 G D x */
    auto project = [&](Vec x, Vec y) -> PetscErrorCode {
      PetscFunctionBegin;
      PetscCall(FETIApplyG(feti, x, c1));
      PetscCall(lift(c1, t));
      PetscCall(VecPointwiseMult(t, D, t));
      if (x == y) PetscCall(VecAXPY(y, -1.0, t));
      else PetscCall(VecWAXPY(y, -1.0, t, x));
      PetscFunctionReturn(PETSC_SUCCESS);
    };
    PetscCall(MatMult(d->F, l, w));
    ++*products;
    PetscCall(VecAYPX(w, -1.0, h)); /* h - F l */
    PetscCall(VecPointwiseMult(w, D, w));
    PetscCall(project(w, r));
    PetscCall(ReproducibleDot(r, r, &rr));
    rr0 = rr;
    PetscCall(VecCopy(r, p));
    while (rr > 0 && rr > 1e-2 * d->rtol * d->rtol * rr0 && its < 2 * d->start_max_it) {
      PetscCall(MatMult(d->F, p, w));
      ++*products;
      PetscCall(VecPointwiseMult(w, D, w));
      PetscCall(project(w, w));
      PetscCall(CGStep(l, r, p, w, &rr, &stepped));
      if (!stepped) break;
      its++;
    }
    /* the gaps: w = F l - h, a = S^-1 G D w, gap = w - G'a */
    PetscCall(MatMult(d->F, l, w));
    ++*products;
    PetscCall(VecAXPY(w, -1.0, h));
    PetscCall(VecPointwiseMult(t, D, w));
    PetscCall(FETIApplyG(feti, t, c1));
    PetscCall(lift(c1, t));
    PetscCall(VecAXPY(w, -1.0, t));
    {
      const PetscScalar *g;
      mingap = PETSC_MAX_REAL;
      PetscCall(VecGetArrayRead(w, &g));
      for (PetscInt row : d->normal) mingap = PetscMin(mingap, PetscRealPart(g[row - d->rstart]));
      PetscCall(VecRestoreArrayRead(w, &g));
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &mingap, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)cp)));
    }
    /* kept only from a converged CG (a breakdown, p'w <= 0, or the step limit is no solution) */
    if (rr <= 1e-2 * d->rtol * d->rtol * rr0 && mingap >= 0) {
      PetscCall(VecCopy(l, lambda));
      PetscCall(MatMult(d->Q, w, t)); /* nu = Q gap */
      PetscCall(TaoSMALXESetStartMultiplier_Private(d->tao, t));
      *found = PETSC_TRUE;
    }
  }
  PetscCall(PetscInfo(cp, "Separated start: |G D l~_D - e| / |e| = %g, %" PetscInt_FMT " CG steps without the contact rows, residual %g of its start, smallest normal gap %g: %s\n", (double)resid, its,
                      (double)(rr0 > 0 ? PetscSqrtReal(rr / rr0) : 0), (double)mingap, *found ? "the solution touches nothing, kept" : "not kept"));
done:
  for (Vec *v : {&D, &l, &r, &p, &w, &t, &c1, &c2}) PetscCall(VecDestroy(v));
  PetscCall(FETICoarseSolverDestroy(cs));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* -contact_start_rtol, -contact_start_max_it, -contact_start_compressive (read in ContactProblemSetFromOptions()'s block) */
PetscErrorCode ContactProblemStartOptions_Private(ContactProblem cp, CONEFETI_OPTIONS_ITEMS PetscOptionsObject)
{
  ContactProblemData *d      = cp->data;
  const char         *prefix = PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "";

  PetscFunctionBegin;
  PetscCall(PetscOptionsReal("-contact_start_rtol",
                             "A cold solve first runs projected CG on the problem without the contact inequalities (nodes bonded) to this relative residual (0: start from the given multipliers)",
                             "ContactProblemSolve", d->start_rtol, &d->start_rtol, NULL));
  PetscCall(PetscOptionsInt("-contact_start_max_it", "Most CG steps of that start (-contact_start_rtol)", "ContactProblemSolve", d->start_max_it, &d->start_max_it, NULL));
  PetscCheck(d->start_rtol >= 0 && d->start_rtol < 1, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE, "-%scontact_start_rtol must be in [0, 1) (0: no start solve), got %g", prefix,
             (double)d->start_rtol);
  PetscCall(
      PetscOptionsReal("-contact_start_separated",
                       "When less than this share of the bonded start's normal force presses, a cold solve first tries the solution without contact rows, kept when it touches nothing (0: never)",
                       "ContactProblemSolve", d->start_separated, &d->start_separated, NULL));
  PetscCheck(d->start_separated >= 0 && d->start_separated <= 1, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE, "-%scontact_start_separated must be in [0, 1], got %g", prefix,
             (double)d->start_separated);
  PetscCall(PetscOptionsReal("-contact_start_compressive", "The start is abandoned (the given multipliers kept) when less than this share of its normal force sum |l_n| is compressive",
                             "ContactProblemSolve", d->start_compressive, &d->start_compressive, NULL));
  PetscCheck(d->start_compressive >= 0 && d->start_compressive <= 1, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE, "-%scontact_start_compressive must be in [0, 1], got %g", prefix,
             (double)d->start_compressive);
  PetscCheck(d->start_max_it >= 1, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE, "-%scontact_start_max_it must be >= 1, got %" PetscInt_FMT, prefix, d->start_max_it);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* lambda <- lambda + y, y in range(P) minimizing the dual energy without the inequalities, by CG on P F P to
   |P(h - F lambda)| <= start_rtol times its start. Only the projector form (FETI's Q): G l = e stays as it was.
   Returns the products with F it took. */
PetscErrorCode ContactProblemStart_Private(ContactProblem cp, Vec lambda, PetscInt *products)
{
  ContactProblemData *d = cp->data;
  Vec                 r, p, w, t, q, lambda0;
  PetscReal           rr, rr0, share = 1;
  PetscBool           stepped;
  PetscInt            its = 0;

  PetscFunctionBegin;
  *products = 0;
  if (!(d->start_rtol > 0) || !d->Q || !d->has_normal) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecDuplicate(lambda, &r));
  PetscCall(VecDuplicate(lambda, &p));
  PetscCall(VecDuplicate(lambda, &w));
  PetscCall(VecDuplicate(lambda, &t));
  PetscCall(VecDuplicate(lambda, &q));
  PetscCall(VecDuplicate(lambda, &lambda0));
  PetscCall(VecCopy(lambda, lambda0));
  PetscCall(MatMult(d->F, lambda, t));
  ++*products;
  PetscCall(VecAYPX(t, -1.0, d->h)); /* h - F lambda */
  PetscCall(Project(d->Q, t, r, q));
  PetscCall(ReproducibleDot(r, r, &rr));
  rr0 = rr;
  PetscCall(VecCopy(r, p));
  while (rr > 0 && rr > d->start_rtol * d->start_rtol * rr0 && its < d->start_max_it) {
    PetscCall(MatMult(d->F, p, t));
    ++*products;
    PetscCall(Project(d->Q, t, w, q)); /* w = P F p */
    PetscCall(CGStep(lambda, r, p, w, &rr, &stepped));
    if (!stepped) break;
    its++;
    if (its >= 2) { /* two steps tell (docs/scale.md): a bonded zone far from the contact zone is mostly in tension */
      PetscCall(CompressiveShare(cp, lambda, &share));
      if (share < d->start_compressive) break;
    }
  }
  PetscCall(CompressiveShare(cp, lambda, &share));
  if (share < d->start_compressive) PetscCall(VecCopy(lambda0, lambda));
  PetscCall(PetscInfo(cp, "Start: %" PetscInt_FMT " CG steps on the problem without the contact inequalities, residual %g of its start (-contact_start_rtol %g), compressive share of |l_n| %g: %s\n",
                      its, (double)(rr0 > 0 ? PetscSqrtReal(rr / rr0) : 0), (double)d->start_rtol, (double)share, share < d->start_compressive ? "abandoned (-contact_start_compressive)" : "kept"));
  if (share < d->start_separated) { /* the bonded zone mostly pulls: perhaps no zone closes at all */
    PetscBool found;
    PetscInt  more;
    PetscCall(SeparatedStart(cp, lambda, &found, &more));
    *products += more;
  }
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&p));
  PetscCall(VecDestroy(&w));
  PetscCall(VecDestroy(&t));
  PetscCall(VecDestroy(&q));
  PetscCall(VecDestroy(&lambda0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
