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
  PetscReal           rr, rr0, rrnew, pw, share = 1;
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
    PetscCall(ReproducibleDot(p, w, &pw));
    if (!(pw > 0)) break; /* F is semidefinite on range(P) only up to rounding */
    const PetscReal alpha = rr / pw;
    PetscCall(ReproducibleAXPY(lambda, alpha, p));
    PetscCall(ReproducibleAXPY(r, -alpha, w));
    PetscCall(ReproducibleDot(r, r, &rrnew));
    PetscCall(ReproducibleAYPX(p, rrnew / rr, r));
    rr = rrnew;
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
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&p));
  PetscCall(VecDestroy(&w));
  PetscCall(VecDestroy(&t));
  PetscCall(VecDestroy(&q));
  PetscCall(VecDestroy(&lambda0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
