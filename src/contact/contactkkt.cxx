/* The KKT residual of a dual contact problem, computed from the multipliers and the equality's multiplier
   alone (not taken from the solver's own test), so that ContactProblemSolve() says "converged" only for
   multipliers that solve the problem it was given.

   With r = F l - h + w (w = G'mu, the equality's multiplier), l solves the problem exactly when
     - G l = e;
     - r_i = 0 on every multiplier without a constraint (gluing, Dirichlet);
     - l_n >= 0, r_n >= 0, l_n r_n = 0 on the normal multipliers;
     - r_t = -s l_t with s >= 0 and |l_t| = g, or r_t = 0 and |l_t| <= g, on the tangential pairs
       (g the Tresca bound, or F max(l_n, 0) for Coulomb: the fixed point is part of the test);
       with friction polygons, each tangential multiplier in [-c g, c g] with r = 0 inside, r <= 0 at c g,
       r >= 0 at -c g (c = sin(pi/(2k)), contactpolygon.cxx).
   Each of the last three is the natural residual l - P(l - k r) (P: the projection onto the set) with k
   the ratio of the multipliers' scale s to the gradient's, so that all are in units of l and relative to s;
   the equality is relative to the larger of |e| and |G|_F max(|l|, s) (projector form: |Q l - Q l~| relative to
   |Q l~|, |l| and s). s = max(max |l|, max |h_free| / ||PFP||), h_free the data of the rows without inequalities;
   the gradient's scale is max(|F l|, |h|) with |h| over every row but the normal ones that carry no force. */
#include <conefeti/private/contactimpl.h>
#include <cmath>
#include <limits>

/*@C
  ContactProblemComputeKKTResidual - The relative KKT residual of multipliers of the dual contact problem,
  computed from scratch: the natural residual of the gradient of the Lagrangian F l - h + G'mu on the set
  (free multipliers, normal multipliers >= 0, friction disks of radius g, with g = F l_n for Coulomb nodes)
  relative to the multipliers' scale s, and the equality residual |G l - e| relative to max(|e|, |G|_F max(|l|, s))
  (projector form: |Q l - Q l~| relative to max(|Q l~|, |l|, s)). s is max |l|, or, when larger, max |h_free| / ||PFP||:
  the force the data of the rows without inequalities (gluing jumps, prescribed displacements) would need, so that
  multipliers at the rounding level (nothing loaded) are measured against their data, not their own rounding.

  Collective

  Input Parameters:
+ cp     - the problem, solved (the equality's multiplier comes from its solver)
- lambda - the multipliers

  Output Parameters:
+ natural  - the natural residual max |l - P(l - k r)| / s (k = s / max(|h|, |F l|))
- equality - the equality residual (0 without an equality)

  Notes:
  Two products with F (the gradient and the solver's multiplier). `ContactProblemSolve()` calls it before it
  reports convergence: a solve whose solver test passed but whose KKT residual exceeds
  the acceptance (-contact_acceptance_factor times -contact_rtol; without the option at most 0.1, or -contact_rtol) gets tighter warm solves (-contact_refine_max), and is reported as
  not converged if it still exceeds it after them.

  Level: intermediate

.seealso: `ContactProblemSolve()`, `ContactModelComputeResiduals()`
@*/
PetscErrorCode ContactProblemComputeKKTResidual(ContactProblem cp, Vec lambda, PetscReal *natural, PetscReal *equality)
{
  ContactProblemData    *d;
  Vec                    r, w, Fl;
  const PetscScalar     *l, *ra;
  PetscReal              lmax, hmax, flmax, k, nat = 0, normest = 0, datascale = 0;
  std::vector<char>      role;
  std::vector<PetscReal> bounds;
  constexpr PetscReal    tiny = std::numeric_limits<PetscReal>::min();
  MPI_Comm               comm;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscValidHeaderSpecific(lambda, VEC_CLASSID, 2);
  d    = cp->data;
  comm = PetscObjectComm((PetscObject)cp);
  PetscCheck(d->tao, comm, PETSC_ERR_ARG_WRONGSTATE, "ContactProblem: solve first");
  PetscCall(VecDuplicate(lambda, &Fl));
  PetscCall(VecDuplicate(lambda, &r));
  PetscCall(VecDuplicate(lambda, &w));
  PetscCall(MatMult(d->F, lambda, Fl));
  PetscCall(TaoSMALXEGetEqualityMultiplier(d->tao, w));
  PetscCall(VecWAXPY(r, -1.0, d->h, Fl));
  PetscCall(VecAXPY(r, 1.0, w));
  PetscCall(VecNorm(lambda, NORM_INFINITY, &lmax));
  PetscCall(VecNorm(Fl, NORM_INFINITY, &flmax));
  lmax = PetscMax(lmax, tiny);

  /* the role of each local multiplier: 0 free, 1 normal, 2 first of a tangential pair, 3 second, 4 of a friction polygon */
  PetscCallCXX(role.assign(d->nlocal, 0));
  PetscCallCXX(bounds.resize(d->normal.size()));
  PetscCall(ContactProblemGetSlipBounds(cp, lambda, bounds.data()));
  for (size_t j = 0; j < d->normal.size(); j++) {
    role[d->normal[j] - d->rstart] = 1;
    if (d->law[j] == CONTACT_FRICTIONLESS) continue;
    if (d->polygon)
      for (PetscInt q = 0; q < d->polygon; q++) role[d->tang[j * d->polygon + q] - d->rstart] = 4;
    else {
      role[d->t1[j] - d->rstart] = 2;
      role[d->t2[j] - d->rstart] = 3;
    }
  }
  {
    /* the multipliers' scale: max |l|, or, when larger, what the jumps the free rows prescribe (gluing, Dirichlet
       displacements) would need, max |h_free| / ||PFP||. A solution at the rounding level (a body moved rigidly
       toward a floor it does not reach: l = 0) is then measured against its data, not against its own rounding.
       The gradient's scale: max |F l|, and |h| over the rows but the normal ones that carry no force. The contact
       rows' gaps stay out of both: a far gap needs no force, and its size (1e9) scaled every residual down until
       l = 0 passed for the solution of a problem whose multipliers reach 2600 */
    const PetscScalar *h, *la;
    PetscReal          hm[2] = {0, 0}; /* free rows; every row but the normal ones without force */
    PetscCall(TaoQPGetNormEstimate(d->tao, &normest));
    PetscCall(VecGetArrayRead(d->h, &h));
    PetscCall(VecGetArrayRead(lambda, &la));
    for (PetscInt i = 0; i < d->nlocal; i++) {
      if (!role[i]) hm[0] = PetscMax(hm[0], PetscAbsScalar(h[i]));
      if (role[i] != 1 || PetscRealPart(la[i]) > 0) hm[1] = PetscMax(hm[1], PetscAbsScalar(h[i]));
    }
    PetscCall(VecRestoreArrayRead(lambda, &la));
    PetscCall(VecRestoreArrayRead(d->h, &h));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, hm, 2, MPIU_REAL, MPIU_MAX, comm));
    hmax = hm[1];
    if (normest > 0) datascale = hm[0] / normest;
    lmax = PetscMax(lmax, datascale);
    k    = lmax / PetscMax(PetscMax(hmax, flmax), tiny);
  }
  PetscCall(VecGetArrayRead(lambda, &l));
  PetscCall(VecGetArrayRead(r, &ra));
  for (PetscInt i = 0; i < d->nlocal; i++) {
    const PetscReal li = PetscRealPart(l[i]), ri = PetscRealPart(ra[i]);
    if (role[i] == 0) nat = PetscMax(nat, PetscAbsReal(k * ri));
    else if (role[i] == 1) nat = PetscMax(nat, PetscAbsReal(li - PetscMax(li - k * ri, 0.0)));
  }
  for (size_t j = 0; j < d->normal.size(); j++) {
    if (d->law[j] == CONTACT_FRICTIONLESS) continue;
    if (d->polygon) { /* friction polygon: each tangential multiplier in its interval [-c g, c g] */
      const PetscReal c = ContactPolygonBoundFactor(d->polygon) * bounds[j];
      for (PetscInt q = 0; q < d->polygon; q++) {
        const PetscInt  i  = d->tang[j * d->polygon + q] - d->rstart;
        const PetscReal li = PetscRealPart(l[i]);
        nat                = PetscMax(nat, PetscAbsReal(li - PetscMin(PetscMax(li - k * PetscRealPart(ra[i]), -c), c)));
      }
      continue;
    }
    const PetscInt  a = d->t1[j] - d->rstart, b = d->t2[j] - d->rstart;
    const PetscReal la = PetscRealPart(l[a]), lb = PetscRealPart(l[b]), g = bounds[j];
    PetscReal       y[2] = {la - k * PetscRealPart(ra[a]), lb - k * PetscRealPart(ra[b])}, ny = std::hypot(y[0], y[1]);
    if (ny > g) y[0] *= g / ny, y[1] *= g / ny;
    nat = PetscMax(nat, std::hypot(la - y[0], lb - y[1]));
  }
  PetscCall(VecRestoreArrayRead(lambda, &l));
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nat, 1, MPIU_REAL, MPIU_MAX, comm));
  if (natural) *natural = nat / lmax;

  if (equality) {
    PetscReal res = 0, scale = 0;
    PetscReal nl;
    PetscCall(VecNorm(lambda, NORM_2, &nl));
    nl = PetscMax(nl, datascale); /* at least the scale s of the natural residual */
    if (d->G) {
      Vec       Gl;
      PetscReal ne, gn = 0;
      PetscBool hasnorm;
      PetscCall(MatCreateVecs(d->G, NULL, &Gl));
      PetscCall(MatMult(d->G, lambda, Gl));
      PetscCall(VecAXPY(Gl, -1.0, d->e));
      PetscCall(VecNorm(Gl, NORM_2, &res));
      PetscCall(VecNorm(d->e, NORM_2, &ne));
      PetscCall(MatHasOperation(d->G, MATOP_NORM, &hasnorm));
      if (hasnorm) PetscCall(MatNorm(d->G, NORM_FROBENIUS, &gn));
      scale = PetscMax(ne, gn * nl); /* |G l| cannot exceed |G|_F |l|: a residual of rounding relative to that */
      PetscCall(VecDestroy(&Gl));
    } else if (d->Q) { /* Q l = Q l~ (|Q| = 1); l~ is any particular solution, not necessarily in range(Q) */
      PetscReal nt;
      Vec       qt;
      PetscCall(VecDuplicate(lambda, &qt));
      PetscCall(MatMult(d->Q, d->lt, qt));
      PetscCall(MatMult(d->Q, lambda, w));
      PetscCall(VecAXPY(w, -1.0, qt));
      PetscCall(VecNorm(w, NORM_2, &res));
      PetscCall(VecNorm(qt, NORM_2, &nt));
      PetscCall(VecDestroy(&qt));
      scale = PetscMax(nt, nl);
    }
    *equality = res / PetscMax(scale, tiny);
  }
  PetscCall(VecDestroy(&Fl));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(PETSC_SUCCESS);
}
