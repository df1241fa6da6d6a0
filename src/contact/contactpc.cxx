/* The preconditioner of the dual contact problem's operator F: a PC of the ContactProblem (options prefix
   -contact_, so -contact_pc_type), handed to smalxe, which uses it in the inner CG steps of the projector form as
   P M P + Q/rho in face (TaoSMALXESetProjectedPreconditioner()). The problem itself knows nothing of F's
   structure and leaves it PCNONE; a ContactModel, whose F is a FETI dual B K+ B', may choose one of FETI's
   (lumped B K B' or Dirichlet B S B', src/feti/fetipc.cxx).

   Only the rows that are not contact rows (gluing, Dirichlet: always free, equalities) are preconditioned by M; the
   contact rows are scaled by c/||F|| instead: M = R M_FETI R + (c/||F||)(I - R), R the 0/1 mask of the non-contact
   rows. Why: in face the solver uses [M]_FF, the principal submatrix of M on the free set. M_FETI approximates
   F^-1, whose principal submatrix is the inverse of the Schur complement F_FF - F_FA F_AA^-1 F_AF, not of F_FF.
   The active contact rows (separated normal multipliers, slipping friction pairs) sit next to free ones on the
   contact surface, where F couples neighbours strongly, so [M_FETI]_FF overshoots there: with M_FETI on every row
   the brick needs more F products than without a preconditioner (docs/scale.md, 'Why n_A grows:
   preconditioning'). The gluing rows are never active, and the contact rows' scaled identity commutes with their
   bounds and disks: the preconditioned CG in face is then CG on the problem in the variables M^-1/2 l of the
   gluing rows, bounds and disks unchanged. c puts the contact rows' spectrum, (c/||F||) F_cc in (0, c], beside the
   preconditioned gluing rows' (about [1, (1 + log(H/h))^2] with the Dirichlet preconditioner).

   The cost of one application: smalxe projects around it (P M' P + Q/rho: two coarse solves, Q g and Q z, each with
   G and G'), so the FETI preconditioner is applied without its own P on both sides (PCFETISetProjected()): M' =
   R M R + (c/||F||)(I - R) with M = B K_bb B' (lumped: one product with K_s per subdomain, no solve) or B S_bb B'
   (Dirichlet: one interior solve, one product with K_s and one with its block K_bi). Without the mask
   (-contact_pc_contact_rows_scaled 0) that is the same operator, P P M P P = P M P; with it, R M R replaces
   R P M P R. -contact_pc_inner_projector restores FETI's pair (two coarse solves more per application). */
#include <conefeti/private/contactimpl.h>
#include <conefeti/private/reproduciblesum.h>

namespace {

struct ContactPCContext {
  ContactProblem cp;      /* not referenced: the problem owns the shell through smalxe */
  PC             inner;   /* the problem's PC (referenced) */
  Vec            mask, w; /* R: 1 on the rows that are not contact rows */
  PetscReal      scale;   /* c of -contact_pc_contact_scale */
};

/* z = R M R g + (c/||F||) (I - R) g */
PetscErrorCode ContactPCApply(PC pc, Vec g, Vec z)
{
  ContactPCContext *c;
  PetscReal         normF;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &c));
  PetscCall(TaoQPGetNormEstimate(c->cp->data->tao, &normF)); /* ||PFP||, estimated by smalxe before the first inner solve */
  PetscCall(VecPointwiseMult(c->w, c->mask, g));
  PetscCall(PCApply(c->inner, c->w, z));
  PetscCall(VecPointwiseMult(z, c->mask, z));
  PetscCall(VecAYPX(c->w, -1.0, g)); /* (I - R) g */
  /* rounded the same on any number of ranks (a BLAS axpy may fuse multiply and add depending on alignment) */
  PetscCall(ReproducibleAXPY(z, c->scale / normF, c->w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ContactPCView(PC pc, PetscViewer viewer)
{
  ContactPCContext *c;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &c));
  PetscCall(PetscViewerASCIIPrintf(viewer, "contact rows scaled by %g/||F||, the other rows preconditioned by:\n", (double)c->scale));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PCView(c->inner, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ContactPCDestroy(PC pc)
{
  ContactPCContext *c;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &c));
  PetscCall(VecDestroy(&c->mask));
  PetscCall(VecDestroy(&c->w));
  PetscCall(PCDestroy(&c->inner));
  delete c;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/*@C
  ContactProblemGetPC - The preconditioner of the operator F that the contact solve uses in face (created
  on first use, type `PCNONE`).

  Collective the first time

  Input Parameter:
. cp - the problem

  Output Parameter:
. pc - the preconditioner (borrowed); options prefix that of the problem followed by contact_

  Options Database Keys:
+ -contact_pc_type <none,lumped,dirichlet>  - its type (none unless the caller chose one; a `ContactModel` chooses dirichlet when at most half the subdomains use dense K+ blocks in F)
. -contact_pc_contact_scale <30>            - c: the contact rows are scaled by c/||F|| instead of preconditioned by M
. -contact_pc_contact_rows_scaled <true>    - false: M on every row, contact rows too (costs F products on the brick)
- -contact_pc_inner_projector <false>       - true: FETI's M applied with its own P on both sides, P M P (two coarse solves more per application)

  Notes:
  Used only in the projector form (`ContactProblemSetProjector()`) and with one inner solver (every pipeline but
  Coulomb's merged algorithm, whose Gauss-Seidel blocks have no preconditioner). The inner CG steps are
  preconditioned in face by P M' P + Q/rho (`TaoSMALXESetProjectedPreconditioner()`), which replaces the penalty
  preconditioner, with M' = R M R + (c/||F||)(I - R), R the mask of the rows that are not contact rows (gluing,
  Dirichlet): M preconditions only the rows that are never active, and the contact rows keep a scaled identity,
  which commutes with their bounds and disks. Smalxe's P on both sides is the only projection by default: a FETI
  M is applied without its own (`PCFETISetProjected()`), two coarse solves per application instead of four. It
  changes the path, not the solution: expansion, proportioning and the stopping tests stay unpreconditioned. The FETI types need F to be a FETI operator (`FETIGetOperators()`).
  Measurements: docs/scale.md, 'Why n_A grows: preconditioning'.

  Level: intermediate

.seealso: `ContactProblemSetUp()`, `TaoSMALXESetProjectedPreconditioner()`, `PCFETILUMPED`, `PCFETIDIRICHLET`
@*/
PetscErrorCode ContactProblemGetPC(ContactProblem cp, PC *pc)
{
  ContactProblemData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscAssertPointer(pc, 2);
  d = cp->data;
  if (!d->pc) {
    const char *prefix;
    PetscCall(PCCreate(PetscObjectComm((PetscObject)cp), &d->pc));
    PetscCall(PetscObjectGetOptionsPrefix((PetscObject)cp, &prefix));
    PetscCall(PCSetOptionsPrefix(d->pc, prefix));
    PetscCall(PCAppendOptionsPrefix(d->pc, "contact_"));
    PetscCall(PCSetType(d->pc, PCNONE));
  }
  *pc = d->pc;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Inside ContactProblemSetFromOptions()'s options block: how the preconditioner is used */
PetscErrorCode ContactProblemPCOptions_Private(ContactProblem cp, CONEFETI_OPTIONS_ITEMS PetscOptionsObject)
{
  ContactProblemData *d = cp->data;

  PetscFunctionBegin;
  PetscCall(PetscOptionsReal("-contact_pc_contact_scale", "With -contact_pc_type: the contact rows are scaled by this over ||F|| instead of preconditioned", "ContactProblemGetPC", d->pc_contact_scale,
                             &d->pc_contact_scale, NULL));
  PetscCall(PetscOptionsBool("-contact_pc_contact_rows_scaled", "With -contact_pc_type: scale the contact rows (true) or precondition them like the gluing rows (false)", "ContactProblemGetPC",
                             d->pc_contact_rows_scaled, &d->pc_contact_rows_scaled, NULL));
  PetscCall(PetscOptionsBool("-contact_pc_inner_projector", "With -contact_pc_type: FETI's M with its own projector on both sides, P M P (true, two coarse solves more per application), or M alone",
                             "ContactProblemGetPC", d->pc_inner_projector, &d->pc_inner_projector, NULL));
  PetscCheck(d->pc_contact_scale > 0 && !PetscIsInfOrNanReal(d->pc_contact_scale), PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE,
             "-%scontact_pc_contact_scale must be finite and > 0, got %g", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", (double)d->pc_contact_scale);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* After that block (an object's options print once under -help, in its first block): the preconditioner's own
   options (-contact_pc_type ...) */
PetscErrorCode ContactProblemSetFromOptionsPC_Private(ContactProblem cp)
{
  PC pc;

  PetscFunctionBegin;
  PetscCall(ContactProblemGetPC(cp, &pc));
  PetscCall(PCSetFromOptions(pc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* At setup: the preconditioner reaches smalxe when it is not PCNONE and the equality is a projector */
PetscErrorCode ContactProblemSetUpPC_Private(ContactProblem cp)
{
  ContactProblemData *d = cp->data;
  PetscBool           none;
  PC                  shell;
  ContactPCContext   *c;
  PetscScalar        *m;

  PetscFunctionBegin;
  if (!d->pc || !d->Q) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscObjectTypeCompare((PetscObject)d->pc, PCNONE, &none));
  if (none) PetscFunctionReturn(PETSC_SUCCESS);
  if (d->pipeline == CONTACT_PIPELINE_COULOMB && d->algorithm == CONTACT_COULOMB_MERGED) { /* its Gauss-Seidel blocks take none */
    PetscCall(PetscInfo(cp, "Coulomb's merged algorithm: the preconditioner in face (-contact_pc_type) is not used\n"));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PCSetOperators(d->pc, d->F, d->F));
  {
    /* a preconditioner in face goes with the projected CG expansion, as mprgp/mpgp choose for an assembled
       Hessian with ICC: the preconditioned CG steps hit the bounds and disks more often, and the projected full
       step adds every constraint it crosses at once (docs/scale.md, 'Why n_A grows: preconditioning'). The
       expansions that find the active set follow one another and first try the last one's length, one product
       each instead of two (TaoQPSetExpansionLagged(); docs/scale.md, 'Lever: the early outer iterations'). An
       option of the inner solver's wins. */
    Tao         sub;
    const char *subprefix;
    PetscBool   given = PETSC_FALSE, given_lagged = PETSC_FALSE, g;

    PetscCall(TaoSMALXEGetSubsolver(d->tao, &sub));
    if (sub) {
      PetscCall(TaoGetOptionsPrefix(sub, &subprefix));
      for (const char *name : {"-tao_mpgp_expansion_projcg", "-tao_mprgp_expansion_projcg"}) {
        PetscCall(PetscOptionsHasName(((PetscObject)sub)->options, subprefix, name, &g));
        given = given || g ? PETSC_TRUE : PETSC_FALSE;
      }
      for (const char *name : {"-tao_mpgp_expansion_lagged", "-tao_mprgp_expansion_lagged"}) {
        PetscCall(PetscOptionsHasName(((PetscObject)sub)->options, subprefix, name, &g));
        given_lagged = given_lagged || g ? PETSC_TRUE : PETSC_FALSE;
      }
      if (!given) PetscCall(TaoQPSetExpansionProjCG(sub, PETSC_TRUE));
      if (!given_lagged) PetscCall(TaoQPSetExpansionLagged(sub, PETSC_TRUE));
    }
  }
  /* smalxe projects around it: FETI's own pair only when asked (see the top) */
  PetscCall(PCFETISetProjected(d->pc, d->pc_inner_projector));
  if (!d->pc_contact_rows_scaled) {
    PetscCall(TaoSMALXESetProjectedPreconditioner(d->tao, d->pc));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCallCXX(c = new ContactPCContext{cp, d->pc, nullptr, nullptr, d->pc_contact_scale});
  PetscCall(PetscObjectReference((PetscObject)d->pc));
  PetscCall(VecDuplicate(d->h, &c->mask));
  PetscCall(VecDuplicate(d->h, &c->w));
  PetscCall(VecSet(c->mask, 1.0));
  PetscCall(VecGetArray(c->mask, &m));
  for (size_t j = 0; j < d->normal.size(); j++) {
    m[d->normal[j] - d->rstart] = 0;
    if (d->polygon)
      for (PetscInt q = 0; q < d->polygon; q++) {
        const PetscInt t = d->tang[j * d->polygon + q];
        if (t >= 0) m[t - d->rstart] = 0;
      }
    else if (d->law[j] != CONTACT_FRICTIONLESS) {
      m[d->t1[j] - d->rstart] = 0;
      m[d->t2[j] - d->rstart] = 0;
    }
  }
  PetscCall(VecRestoreArray(c->mask, &m));
  PetscCall(PCSetUp(d->pc));
  PetscCall(PCCreate(PetscObjectComm((PetscObject)cp), &shell));
  PetscCall(PCSetType(shell, PCSHELL));
  PetscCall(PCSetOperators(shell, d->F, d->F));
  PetscCall(PCShellSetContext(shell, c));
  PetscCall(PCShellSetApply(shell, ContactPCApply));
  PetscCall(PCShellSetDestroy(shell, ContactPCDestroy));
  PetscCall(PCShellSetView(shell, ContactPCView));
  PetscCall(PCShellSetName(shell, "M on the rows that are not contact rows, c/||F|| on the contact rows"));
  PetscCall(TaoSMALXESetProjectedPreconditioner(d->tao, shell));
  PetscCall(PCDestroy(&shell));
  PetscFunctionReturn(PETSC_SUCCESS);
}
