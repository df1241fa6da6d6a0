/* Options and the norm estimate of the MPRGP/MPGP core, shared by the TAO and KSP types. */
#include <cstring>
#include <conefeti/private/mpgpcore.h>
#include <petsc/private/taoimpl.h>

namespace {

/* An option as PetscOptions*() take it (key: -<kind>_<name>_<what>, the object's prefix added by them)
   and as the user types it (shown: with the object's prefix, e.g. -contact_tao_smalxe_subsolver_tao_mpgp_gamma),
   so that error messages name the option that was actually given. */
struct OptionName {
  char key[64], shown[320];
};

PetscErrorCode MakeOptionName(const char *prefix, const char *kind, const char *name, const char *what, OptionName *o)
{
  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(o->key, sizeof(o->key), "-%s_%s_%s", kind, name, what));
  PetscCall(PetscSNPrintf(o->shown, sizeof(o->shown), "-%s%s", prefix ? prefix : "", o->key + 1));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* prefix: the object's options prefix (may be NULL); kind: "tao" or "ksp"; name: "mprgp" or "mpgp" */
PetscErrorCode MPGPCoreSetFromOptions(CONEFETI_OPTIONS_ITEMS PetscOptionsObject, MPI_Comm comm, const char *prefix, const char *kind, const char *name, MPGPCore *core, QPNormSettings *norm,
                                      PetscBool *counters_view)
{
  char       title[64];
  OptionName opt, gamma, alpha, normopt;
  PetscReal  value;
  PetscBool  set;

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(title, sizeof(title), "%s %s: QP over a separable set (conefeti)", kind, name));
  PetscOptionsHeadBegin(PetscOptionsObject, title);
  PetscCall(MakeOptionName(prefix, kind, name, "gamma", &gamma));
  PetscCall(PetscOptionsReal(gamma.key, "Proportioning parameter Gamma > 0 (|beta|^2 <= Gamma^2 phi~.phi means proportional)", "MPGP", core->gamma, &core->gamma, NULL));
  /* an infinite Gamma would call every iterate proportional (and Gamma^2 phi~.phi is NaN when phi~ = 0) */
  PetscCheck(core->gamma > 0 && !PetscIsInfOrNanReal(core->gamma), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be finite and > 0, got %g", gamma.shown, (double)core->gamma);
  PetscCall(MakeOptionName(prefix, kind, name, "alpha", &alpha));
  PetscCall(PetscOptionsReal(alpha.key, "Fixed step length as a multiple of 1/||A||, in (0, 2]", "MPGP", core->alpha_scale, &core->alpha_scale, NULL));
  if (core->variant == MPGPVariant::MPGP) {
    PetscCall(MakeOptionName(prefix, kind, name, "bb", &opt));
    PetscCall(PetscOptionsBool(opt.key, "Try Barzilai-Borwein lengths in gradient projection steps (kept only when q decreases)", "MPGP", core->bb, &core->bb, NULL));
    PetscCall(MakeOptionName(prefix, kind, name, "arc", &opt));
    PetscCall(PetscOptionsReal(opt.key, "CG steps also move a disk block on its circle along the circle while alpha |g.nu|/r <= this (0: such blocks move only in projected steps)", "MPGP", core->arc,
                               &core->arc, NULL));
    PetscCheck(core->arc >= 0 && !PetscIsInfOrNanReal(core->arc), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be finite and >= 0, got %g", opt.shown, (double)core->arc);
  }
  PetscCall(MakeOptionName(prefix, kind, name, "expansion_projcg", &opt));
  PetscCall(PetscOptionsBool(opt.key, "Expansion steps first try the projected full CG step P(x - a_cg p), kept when q is no higher than at the feasible half step (default: Dostal's expansion only)",
                             "MPGP", core->projcg, &core->projcg, NULL));
  PetscCall(MakeOptionName(prefix, kind, name, "norm", &normopt));
  PetscCall(PetscOptionsReal(normopt.key, "Use this value of ||A|| instead of estimating it", strcmp(kind, "ksp") ? "TaoQPSetNormEstimate" : "KSPQPSetNormEstimate", norm->user, &value, &set));
  if (set) {
    PetscCheck(value >= 0 && !PetscIsInfOrNanReal(value), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be finite and > 0 (0 to estimate), got %g", normopt.shown, (double)value);
    norm->user = value;
  }
  PetscCall(MakeOptionName(prefix, kind, name, "norm_method", &opt));
  PetscCall(PetscOptionsEnum(opt.key, "How ||A|| is estimated", "MatQPEstimateNorm", QPNormMethods, (PetscEnum)norm->method, (PetscEnum *)&norm->method, NULL));
  PetscCheck(norm->method != QP_NORM_USER || norm->user > 0, comm, PETSC_ERR_ARG_WRONG, "%s user needs %s <value>", opt.shown, normopt.shown);
  PetscCall(MakeOptionName(prefix, kind, name, "norm_margin", &opt));
  PetscCall(PetscOptionsReal(opt.key, "Relative safety margin added to the norm estimate (default 0.01 for slepc, 0.05 for power)", "MatQPEstimateNorm", norm->margin, &norm->margin, NULL));
  /* a negative margin stands for the method's default; a NaN would silently become that default too */
  PetscCheck(!PetscIsInfOrNanReal(norm->margin), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be finite (>= 0, or negative for the method's default), got %g", opt.shown, (double)norm->margin);
  PetscCall(MakeOptionName(prefix, kind, name, "counters_view", &opt));
  PetscCall(PetscOptionsBool(opt.key, "Print the counters as one JSON line after each solve", "QPCountersViewJSON", *counters_view, counters_view, NULL));
  PetscOptionsHeadEnd();
  PetscCheck(core->alpha_scale > 0 && core->alpha_scale <= 2, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be in (0, 2], got %g", alpha.shown, (double)core->alpha_scale);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* objprefix: the solver's options prefix (may be NULL); kind, name as above */
PetscErrorCode QPNormSettingsApply(QPNormSettings *norm, Mat A, const char *objprefix, const char *kind, const char *name, QPCounters *counters)
{
  PetscInt products;
  char     prefix[256];

  PetscFunctionBegin;
  if (norm->user > 0) {
    norm->used = norm->user;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%s%s_%s_norm_", objprefix ? objprefix : "", kind, name));
  PetscCall(MatQPEstimateNorm(A, norm->method, norm->margin >= 0 ? norm->margin : (norm->method == QP_NORM_SLEPC ? 0.01 : 0.05), prefix, &norm->used, &products));
  counters->estimate_mults += products;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* one line on how expansion steps are done, one on the proportioning steps' length and one on arc steps (MPGP) */
PetscErrorCode MPGPCoreViewExpansion(const MPGPCore *core, PetscViewer viewer)
{
  PetscFunctionBegin;
  if (core->projcg)
    PetscCall(PetscViewerASCIIPrintf(viewer, "expansion: projected full CG step first (%" PetscInt_FMT " not kept), else feasible half step and fixed-length projected step\n", core->projcg_rejected));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "expansion: feasible half step and fixed-length projected step\n"));
  if (core->variant == MPGPVariant::MPGP) {
    if (core->bb)
      PetscCall(PetscViewerASCIIPrintf(viewer, "proportioning steps: Barzilai-Borwein length first, kept when q decreases (%" PetscInt_FMT " not kept), else the fixed length\n", core->bb_rejected));
    else PetscCall(PetscViewerASCIIPrintf(viewer, "proportioning steps: fixed length\n"));
  }
  if (core->variant == MPGPVariant::MPGP && core->arc > 0)
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "arc steps: CG steps move disk blocks on their circle along it while alpha |g.nu|/r <= %g: %" PetscInt_FMT " steps, %" PetscInt_FMT
                                     " replaced by projected steps, %" PetscInt_FMT " gradients recomputed for them\n",
                                     (double)core->arc, core->arc_steps, core->arc_rejected, core->arc_refreshed));
  else if (core->variant == MPGPVariant::MPGP) PetscCall(PetscViewerASCIIPrintf(viewer, "arc steps: off (disk blocks on their circle move only in projected steps)\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* TAO's tolerances as the QP types read them: gatol and gttol, and grtol (mprgp, mpgp) or catol and crtol
   (equality, smalxe). TaoSetFromOptions() and TaoSetTolerances() take a NaN, which makes every test false
   and the solve run to its iteration limit, so they are checked when a solve starts. */
PetscErrorCode TaoQPCheckTolerances_Private(Tao tao, PetscBool equality)
{
  const char *prefix;
  struct {
    const char *name;
    PetscReal   value;
  } const tols[] = {{"gatol", tao->gatol}, {"gttol", tao->gttol}, {equality ? "catol" : "grtol", equality ? tao->catol : tao->grtol}, {equality ? "crtol" : NULL, tao->crtol}};

  PetscFunctionBegin;
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  for (const auto &t : tols) {
    if (!t.name) continue;
    PetscCheck(t.value >= 0 && !PetscIsInfOrNanReal(t.value), PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "-%stao_%s must be finite and >= 0, got %g", prefix ? prefix : "", t.name,
               (double)t.value);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
