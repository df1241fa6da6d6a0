/* Options and the norm estimate of the MPRGP/MPGP core, shared by the TAO and KSP types. */
#include <cstdio>
#include <conefeti/private/mpgpcore.h>
#include <petsc/private/taoimpl.h>

const MPGPOptionNames MPGPOptionsTaoMPRGP = {"TAO mprgp: QP over a separable set (conefeti)",
                                             "-tao_mprgp_gamma",
                                             "-tao_mprgp_alpha",
                                             NULL,
                                             NULL,
                                             "-tao_mprgp_expansion_projcg",
                                             "-tao_mprgp_expansion_lagged",
                                             "-tao_mprgp_expansion_lookahead",
                                             "-tao_mprgp_expansion_gradient",
                                             "-tao_mprgp_norm",
                                             "-tao_mprgp_norm_method",
                                             "-tao_mprgp_norm_margin",
                                             "-tao_mprgp_counters_view",
                                             "tao_mprgp_",
                                             "tao_mprgp_norm_"};
const MPGPOptionNames MPGPOptionsTaoMPGP  = {"TAO mpgp: QP over a separable set (conefeti)",
                                             "-tao_mpgp_gamma",
                                             "-tao_mpgp_alpha",
                                             "-tao_mpgp_bb",
                                             "-tao_mpgp_arc",
                                             "-tao_mpgp_expansion_projcg",
                                             "-tao_mpgp_expansion_lagged",
                                             "-tao_mpgp_expansion_lookahead",
                                             "-tao_mpgp_expansion_gradient",
                                             "-tao_mpgp_norm",
                                             "-tao_mpgp_norm_method",
                                             "-tao_mpgp_norm_margin",
                                             "-tao_mpgp_counters_view",
                                             "tao_mpgp_",
                                             "tao_mpgp_norm_"};
const MPGPOptionNames MPGPOptionsKSPMPRGP = {"KSP mprgp: QP over a separable set (conefeti)",
                                             "-ksp_mprgp_gamma",
                                             "-ksp_mprgp_alpha",
                                             NULL,
                                             NULL,
                                             "-ksp_mprgp_expansion_projcg",
                                             "-ksp_mprgp_expansion_lagged",
                                             "-ksp_mprgp_expansion_lookahead",
                                             "-ksp_mprgp_expansion_gradient",
                                             "-ksp_mprgp_norm",
                                             "-ksp_mprgp_norm_method",
                                             "-ksp_mprgp_norm_margin",
                                             "-ksp_mprgp_counters_view",
                                             "ksp_mprgp_",
                                             "ksp_mprgp_norm_"};
const MPGPOptionNames MPGPOptionsKSPMPGP  = {"KSP mpgp: QP over a separable set (conefeti)",
                                             "-ksp_mpgp_gamma",
                                             "-ksp_mpgp_alpha",
                                             "-ksp_mpgp_bb",
                                             "-ksp_mpgp_arc",
                                             "-ksp_mpgp_expansion_projcg",
                                             "-ksp_mpgp_expansion_lagged",
                                             "-ksp_mpgp_expansion_lookahead",
                                             "-ksp_mpgp_expansion_gradient",
                                             "-ksp_mpgp_norm",
                                             "-ksp_mpgp_norm_method",
                                             "-ksp_mpgp_norm_margin",
                                             "-ksp_mpgp_counters_view",
                                             "ksp_mpgp_",
                                             "ksp_mpgp_norm_"};

namespace {

/* An option as the user types it, with the object's prefix (e.g. -contact_tao_smalxe_subsolver_tao_mpgp_gamma),
   so that error messages name the option that was actually given. */
struct ShownName {
  char text[320];
};

ShownName Shown(const char *prefix, const char *key)
{
  ShownName s;
  std::snprintf(s.text, sizeof(s.text), "-%s%s", prefix ? prefix : "", key + 1);
  return s;
}

} // namespace

/* prefix: the object's options prefix (may be NULL) */
PetscErrorCode MPGPCoreSetFromOptions(CONEFETI_OPTIONS_ITEMS PetscOptionsObject, MPI_Comm comm, const char *prefix, const MPGPOptionNames *names, MPGPCore *core, QPNormSettings *norm,
                                      PetscBool *counters_view)
{
  PetscReal value;
  PetscBool set;

  PetscFunctionBegin;
  PetscOptionsHeadBegin(PetscOptionsObject, names->title);
  PetscCall(PetscOptionsReal(names->gamma, "Proportioning parameter Gamma > 0 (|beta|^2 <= Gamma^2 phi~.phi means proportional)", "MPGP", core->gamma, &core->gamma, NULL));
  /* an infinite Gamma would call every iterate proportional (and Gamma^2 phi~.phi is NaN when phi~ = 0) */
  PetscCheck(core->gamma > 0 && !PetscIsInfOrNanReal(core->gamma), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be finite and > 0, got %g", Shown(prefix, names->gamma).text, (double)core->gamma);
  PetscCall(PetscOptionsReal(names->alpha, "Fixed step length as a multiple of 1/||A||, in (0, 2]", "MPGP", core->alpha_scale, &core->alpha_scale, NULL));
  if (core->variant == MPGPVariant::MPGP) {
    PetscCall(PetscOptionsBool(names->bb, "Try Barzilai-Borwein lengths in gradient projection steps (kept only when q decreases)", "MPGP", core->bb, &core->bb, NULL));
    PetscCall(PetscOptionsReal(names->arc, "CG steps also move a disk block on its circle along the circle while alpha |g.nu|/r <= this (0: such blocks move only in projected steps)", "MPGP",
                               core->arc, &core->arc, NULL));
    PetscCheck(core->arc >= 0 && !PetscIsInfOrNanReal(core->arc), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be finite and >= 0, got %g", Shown(prefix, names->arc).text, (double)core->arc);
  }
  PetscCall(PetscOptionsBool(names->expansion_projcg,
                             "Expansion steps first try the projected full CG step P(x - a_cg p), kept when q is no higher than at the feasible half step (default: Dostal's expansion only)", "MPGP",
                             core->projcg, &core->projcg, NULL));
  PetscCall(PetscOptionsBool(names->expansion_lagged,
                             "With the projected CG expansion: an expansion first tries the projected step with the last expansion's length, without its own product, kept when q falls",
                             names->expansion_lagged[1] == 'k' ? "MPGP" : "TaoQPSetExpansionLagged", core->lagged, &core->lagged, NULL));
  PetscCall(PetscOptionsInt(names->expansion_lookahead,
                            "With the projected CG expansion: the projected step continues that many more CG steps in the face first, past the set, then projects (0: one step)", "MPGP",
                            core->lookahead, &core->lookahead, NULL));
  PetscCheck(core->lookahead >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be >= 0, got %" PetscInt_FMT, Shown(prefix, names->expansion_lookahead).text, core->lookahead);
  PetscCall(PetscOptionsBool(names->expansion_gradient,
                             "With the projected CG expansion: the tried point also takes the fixed-length projected gradient step from the CG point, P(y - alpha g(y)), y = x - a_cg p", "MPGP",
                             core->projcg_gradient, &core->projcg_gradient, NULL));
  PetscCall(PetscOptionsReal(names->norm, "Use this value of ||A|| instead of estimating it", names->norm[1] == 'k' ? "KSPQPSetNormEstimate" : "TaoQPSetNormEstimate", norm->user, &value, &set));
  if (set) {
    PetscCheck(value >= 0 && !PetscIsInfOrNanReal(value), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be finite and > 0 (0 to estimate), got %g", Shown(prefix, names->norm).text, (double)value);
    norm->user = value;
  }
  PetscCall(PetscOptionsEnum(names->norm_method, "How ||A|| is estimated", "MatQPEstimateNorm", QPNormMethods, (PetscEnum)norm->method, (PetscEnum *)&norm->method, NULL));
  PetscCheck(norm->method != QP_NORM_USER || norm->user > 0, comm, PETSC_ERR_ARG_WRONG, "%s user needs %s <value>", Shown(prefix, names->norm_method).text, Shown(prefix, names->norm).text);
  PetscCall(PetscOptionsReal(names->norm_margin, "Relative safety margin added to the norm estimate (default 0.01 for slepc, 0.05 for power)", "MatQPEstimateNorm", norm->margin, &norm->margin, NULL));
  /* a negative margin stands for the method's default; a NaN would silently become that default too */
  PetscCheck(!PetscIsInfOrNanReal(norm->margin), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be finite (>= 0, or negative for the method's default), got %g", Shown(prefix, names->norm_margin).text,
             (double)norm->margin);
  PetscCall(PetscOptionsBool(names->counters_view, "Print the counters as one JSON line after each solve", "QPCountersViewJSON", *counters_view, counters_view, NULL));
  PetscOptionsHeadEnd();
  PetscCheck(core->alpha_scale > 0 && core->alpha_scale <= 2, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be in (0, 2], got %g", Shown(prefix, names->alpha).text, (double)core->alpha_scale);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* objprefix: the solver's options prefix (may be NULL) */
PetscErrorCode QPNormSettingsApply(QPNormSettings *norm, Mat A, const char *objprefix, const MPGPOptionNames *names, QPCounters *counters)
{
  PetscInt products;
  char     prefix[256];

  PetscFunctionBegin;
  if (norm->user > 0) {
    norm->used = norm->user;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%s%s", objprefix ? objprefix : "", names->norm_prefix));
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
  if (core->projcg && core->projcg_gradient) PetscCall(PetscViewerASCIIPrintf(viewer, "expansion: the projected CG step also takes the fixed-length gradient step from the CG point\n"));
  if (core->projcg && core->lookahead > 0)
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "expansion: the projected CG step looks %" PetscInt_FMT " CG steps ahead in the face before it projects (%" PetscInt_FMT " kept, %" PetscInt_FMT " not kept)\n",
                                     core->lookahead, core->lookahead_kept, core->lookahead_rejected));
  if (core->projcg && core->lagged)
    PetscCall(PetscViewerASCIIPrintf(viewer, "expansion: lagged lengths tried first (%" PetscInt_FMT " kept, %" PetscInt_FMT " not kept)\n", core->lagged_steps, core->lagged_rejected));
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
  } const tols[] = {{"tao_gatol", tao->gatol}, {"tao_gttol", tao->gttol}, {equality ? "tao_catol" : "tao_grtol", equality ? tao->catol : tao->grtol}, {equality ? "tao_crtol" : NULL, tao->crtol}};

  PetscFunctionBegin;
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  for (const auto &t : tols) {
    if (!t.name) continue;
    PetscCheck(t.value >= 0 && !PetscIsInfOrNanReal(t.value), PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "-%s%s must be finite and >= 0, got %g", prefix ? prefix : "", t.name,
               (double)t.value);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* TaoSetFromOptions() and TaoSetMaximumIterations() take a negative -tao_max_it, and the solve then ran as with 0: checked
   in the types' TaoSetFromOptions() (the option) and when a solve starts (TaoSetMaximumIterations()) */
PetscErrorCode TaoQPCheckMaxIt_Private(Tao tao)
{
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  PetscCheck(tao->max_it >= 0, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "-%stao_max_it must be >= 0, got %" PetscInt_FMT, prefix ? prefix : "", tao->max_it);
  PetscFunctionReturn(PETSC_SUCCESS);
}
