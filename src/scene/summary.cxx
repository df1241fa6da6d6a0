/* The summary of a solved scene: the pipeline, the counts of the seed paper's tables, times, the
   mechanical residuals; printed as a human table and as one JSON line (docs/output.md). */
#include "sceneimpl.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <strings.h>
#include <string>

/* the type of a TAO once it has one; else keep the default given */
static PetscErrorCode TaoTypeOr(Tao tao, TaoType *type)
{
  TaoType t;

  PetscFunctionBegin;
  PetscCall(TaoGetType(tao, &t));
  if (t) *type = t;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneGetPipelineDescription - The pipeline the scene's zones call for and the solvers it runs (after `ContactSceneSetUp()`).

  Collective

  Input Parameters:
+ scene - the scene, set up
- len   - size of description

  Output Parameters:
+ pipeline    - linear, frictionless, tresca or coulomb (or NULL)
. algorithm   - the Coulomb algorithm that will run (or NULL)
- description - one line naming the pipeline and its solvers (or NULL)

  Level: beginner

.seealso: `ContactSceneSetUp()`, `ContactModelGetPipeline()`
@*/
PetscErrorCode ContactSceneGetPipelineDescription(ContactScene scene, ContactPipeline *pipeline, ContactCoulombAlgorithm *algorithm, char description[], size_t len)
{
  Scene_Impl             &impl = *scene->impl;
  ContactPipeline         pipe;
  ContactCoulombAlgorithm alg = CONTACT_COULOMB_MONOLITHIC;
  char                    buf[256];

  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  PetscCheck(impl.setup, PetscObjectComm((PetscObject)scene), PETSC_ERR_ORDER, "Call ContactSceneSetUp() first");
  PetscCall(ContactModelGetPipeline(impl.cm, &pipe));
  /* the algorithm: the solve's own statistics once it ran, else what the contact problem says it will run */
  if (impl.solved) {
    ContactStatistics st;
    PetscCall(ContactModelGetStatistics(impl.cm, &st));
    alg = st.algorithm;
  } else if (pipe == CONTACT_PIPELINE_COULOMB) {
    ContactProblem cp;
    PetscCall(ContactModelGetContactProblem(impl.cm, &cp));
    PetscCall(ContactProblemGetCoulombAlgorithm(cp, &alg));
  }
  if (pipe == CONTACT_PIPELINE_LINEAR) {
    FETI      feti;
    KSP       ksp;
    PC        pc;
    KSPType   ktype;
    PCType    ptype;
    PetscBool iscg;
    PetscCall(ContactModelGetFETI(impl.cm, &feti));
    PetscCall(FETIGetKSP(feti, &ksp));
    PetscCall(KSPGetType(ksp, &ktype));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCGetType(pc, &ptype));
    /* mprgp and mpgp without bounds are CG (same iterates, reproducible sums) */
    PetscCall(PetscStrcmp(ktype, KSPCG, &iscg));
    if (!iscg) PetscCall(PetscStrcmp(ktype, KSPMPRGP, &iscg));
    if (!iscg) PetscCall(PetscStrcmp(ktype, KSPMPGP, &iscg));
    PetscCall(PetscSNPrintf(buf, sizeof(buf), "linear: no contact zone; FETI %s (KSP %s, preconditioner %s)", iscg ? "projected conjugate gradients" : "projected Krylov solve", ktype ? ktype : "?",
                            ptype ? ptype : "none"));
  } else {
    ContactProblem cp;
    Tao            tao, sub = NULL, sub0 = NULL, sub1 = NULL;
    /* the inner solvers get their types at the first solve: until then, the ones smalxe picks for the
       blocks' sets (mprgp for bounds, mpgp for disks), unless options chose others */
    TaoType  type = NULL, stype = pipe == CONTACT_PIPELINE_FRICTIONLESS ? TAOMPRGP : TAOMPGP, s0 = TAOMPRGP, s1 = TAOMPGP;
    PetscInt polygon;
    PetscCall(ContactModelGetContactProblem(impl.cm, &cp));
    PetscCall(ContactProblemGetFrictionPolygon(cp, &polygon, NULL));
    if (polygon) stype = TAOMPRGP; /* friction polygons: bounds only */
    PetscCall(ContactProblemGetTao(cp, &tao));
    PetscCall(TaoGetType(tao, &type));
    if (pipe == CONTACT_PIPELINE_COULOMB && alg == CONTACT_COULOMB_MERGED) {
      PetscCall(TaoSMALXEGetBlockSubsolver(tao, 0, &sub0));
      PetscCall(TaoSMALXEGetBlockSubsolver(tao, 1, &sub1));
      if (sub0) PetscCall(TaoTypeOr(sub0, &s0));
      if (sub1) PetscCall(TaoTypeOr(sub1, &s1));
    } else {
      PetscCall(TaoSMALXEGetSubsolver(tao, &sub));
      if (sub) PetscCall(TaoTypeOr(sub, &stype));
    }
    switch (pipe) {
    case CONTACT_PIPELINE_FRICTIONLESS:
      PetscCall(PetscSNPrintf(buf, sizeof(buf), "frictionless: %s + %s on the normal multipliers (no tangential multipliers)", type ? type : "?", stype ? stype : "?"));
      break;
    case CONTACT_PIPELINE_TRESCA:
      PetscCall(PetscSNPrintf(buf, sizeof(buf), "tresca: one %s + %s solve (%s of the given slip bounds)", type ? type : "?", stype ? stype : "?", polygon ? "polygons" : "disks"));
      break;
    case CONTACT_PIPELINE_COULOMB:
      if (alg == CONTACT_COULOMB_MSA)
        PetscCall(
            PetscSNPrintf(buf, sizeof(buf), "coulomb, Algorithm 1 (msa): successive approximations of the slip bounds, each a full %s + %s Tresca solve", type ? type : "?", stype ? stype : "?"));
      else if (alg == CONTACT_COULOMB_MERGED)
        PetscCall(PetscSNPrintf(buf, sizeof(buf), "coulomb, Algorithm 2 (merged): one %s loop, each step a block Gauss-Seidel sweep: %s on normal and gluing multipliers, %s on disks of radius F l_n",
                                type ? type : "?", s0 ? s0 : "?", s1 ? s1 : "?"));
      else
        PetscCall(PetscSNPrintf(buf, sizeof(buf), "coulomb, monolithic: one %s loop, one %s over all multipliers, %s F l_n updated before each inner solve", type ? type : "?", stype ? stype : "?",
                                polygon ? "slip bounds" : "disk radii"));
      break;
    default: PetscCall(PetscSNPrintf(buf, sizeof(buf), "%s", ContactPipelines[pipe])); break;
    }
    if (polygon && pipe != CONTACT_PIPELINE_FRICTIONLESS) {
      size_t used = strlen(buf);
      PetscCall(
          PetscSNPrintf(buf + used, sizeof(buf) - used, "; each friction disk replaced by an inscribed %" PetscInt_FMT "-gon (%" PetscInt_FMT " bounded multipliers per node)", 2 * polygon, polygon));
    }
  }
  if (pipeline) *pipeline = pipe;
  if (algorithm) *algorithm = alg;
  if (description) PetscCall(PetscStrncpy(description, buf, len));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneGetSummary - Collect the summary of the last solve: counts, times, the mechanical residuals (computed from u and lambda) and the node states.

  Collective

  Input Parameter:
. scene - the scene, solved

  Output Parameter:
. s - the summary

  Level: beginner

.seealso: `ContactSceneSummary`, `ContactSceneSummaryView()`, `ContactSceneSummaryViewJSON()`
@*/
PetscErrorCode ContactSceneGetSummary(ContactScene scene, ContactSceneSummary *s)
{
  Scene_Impl        &impl = *scene->impl;
  MPI_Comm           comm;
  FETI               feti;
  ContactProblem     cp;
  ContactStatistics  st;
  Mat                B;
  Vec                c, lambda;
  const FETIRowKind *kinds;
  PetscInt           nlocal, counts[4] = {0, 0, 0, 0}, ndir;
  IS                 dir;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  comm = PetscObjectComm((PetscObject)scene);
  PetscCheck(impl.solved, comm, PETSC_ERR_ORDER, "Call ContactSceneSolve() before ContactSceneGetSummary()");
  PetscCall(PetscLogEventBegin(CONTACTSCENE_Summary, scene, 0, 0, 0));
  *s = ContactSceneSummary{};
  PetscCall(PetscStrncpy(s->scene, impl.name.c_str(), sizeof(s->scene)));
  PetscCallMPI(MPI_Comm_size(comm, &s->ranks));
  PetscCall(ContactSceneGetPipelineDescription(scene, &s->pipeline, &s->algorithm, s->description, sizeof(s->description)));
  /* sizes: n as the seed paper counts it (undecomposed mesh, Dirichlet dofs left out) */
  for (size_t b = 0; b < impl.bodies.size(); b++) {
    PetscInt nn;
    PetscCall(FEMGetBodyNodes(impl.fem, (PetscInt)b, &nn, NULL));
    s->n += 3 * nn;
  }
  PetscCall(FEMGetGlobalDirichletDofs(impl.fem, &dir));
  PetscCall(ISGetSize(dir, &ndir));
  PetscCall(ISDestroy(&dir));
  s->n -= ndir;
  PetscCall(ContactModelGetFETI(impl.cm, &feti));
  PetscCall(FETIGetSizes(feti, &s->n_primal, &s->m, &s->rigid_modes));
  PetscCall(FETIGetKplusExplicit(feti, &s->kplus_explicit, &s->kplus_fallback));
  PetscCall(FETIGetKplusType(feti, &s->kplus_type, &s->kplus_blocks));
  PetscCall(FETIGetKplusPrecision(feti, &s->kplus_precision, &s->kplus_single, &s->kplus_factor_bytes, &s->kplus_factor_double_bytes));
  PetscCall(FEMGetNumSubdomains(impl.fem, &s->subdomains, NULL, NULL));
  if (s->pipeline != CONTACT_PIPELINE_LINEAR) { /* the linear solve's options are read (FETISetFromOptions()), so PETSc does not call them unused */
    const char *prefix;
    char       *all;
    PetscCall(PetscObjectGetOptionsPrefix((PetscObject)feti, &prefix));
    PetscCall(PetscOptionsGetAll(NULL, &all));
    std::string ksp, pc;
    PetscCallCXX(ksp = "-" + std::string(prefix ? prefix : "") + "feti_ksp_");
    PetscCallCXX(pc = "-" + std::string(prefix ? prefix : "") + "feti_pc_");
    /* option names are case-insensitive; a token that begins with '-' and this name is an option, not a value */
    for (char *tok = std::strtok(all, " "); tok; tok = std::strtok(NULL, " "))
      if (!strncasecmp(tok, ksp.c_str(), ksp.size()) || !strncasecmp(tok, pc.c_str(), pc.size())) {
        PetscCall(PetscStrncpy(s->linear_option, tok, sizeof(s->linear_option)));
        break;
      }
    PetscCall(PetscFree(all));
  }
  PetscCall(FETIGetConstraints(feti, &B, &c, &kinds));
  PetscCall(ContactModelGetSolution(impl.cm, &lambda, NULL));
  PetscCall(ConeFETIVecFingerprint(lambda, s->fingerprint));
  PetscCall(VecGetLocalSize(lambda, &nlocal));
  for (PetscInt i = 0; i < nlocal; i++) counts[kinds[i]]++;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 4, MPIU_INT, MPI_SUM, comm));
  s->m_gluing     = counts[FETI_ROW_GLUING];
  s->m_dirichlet  = counts[FETI_ROW_DIRICHLET];
  s->m_normal     = counts[FETI_ROW_CONTACT_NORMAL];
  s->m_tangential = counts[FETI_ROW_CONTACT_TANGENTIAL];
  /* the solve */
  PetscCall(ContactModelGetStatistics(impl.cm, &st));
  s->iter         = st.outer_iterations;
  s->al_iter      = st.al_iterations;
  s->n_A_qpp      = st.products_qpp;
  s->n_A_qpq      = st.products_qpq;
  s->n_A          = st.products_qpp + st.products_qpq;
  s->n_A_other    = st.products_other;
  s->n_A_estimate = st.products_estimate;
  PetscCall(FETIGetCoarseSolveCount(feti, &s->coarse_solves));
  s->fixed_point = st.fixed_point;
  s->feasibility = st.feasibility;
  s->acceptance  = st.acceptance;
  s->refinements = st.refinements;
  PetscCall(PetscStrncpy(s->failed_check, st.failed_check, sizeof(s->failed_check)));
  s->time_setup = impl.time_setup;
  s->time_solve = impl.time_solve;
  for (int ph = 0; ph < CONEFETI_PHASE_COUNT; ph++) s->time_phases[ph] = impl.time_phases[ph];
  PetscCallMPI(MPI_Bcast(s->time_phases, CONEFETI_PHASE_COUNT, MPIU_REAL, 0, comm)); /* rank 0's, as the table's times */
  PetscCall(ContactModelGetContactProblem(impl.cm, &cp));
  if (cp) {
    Tao tao;
    PetscCall(ContactProblemGetTao(cp, &tao));
    PetscCall(TaoQPGetNormEstimate(tao, &s->norm_F));
    PetscCall(TaoGetTolerances(tao, NULL, NULL, &s->rtol));
    PetscCall(ContactProblemGetFrictionPolygon(cp, &s->friction_polygon, NULL));
  }
  PetscCall(ContactModelGetUnmatchedNodes(impl.cm, &s->unmatched_nodes));
  PetscCall(ContactModelGetLeftOutNodes(impl.cm, &s->left_out_friction, &s->left_out_overlapping, &s->left_out_overlap));
  PetscCall(ContactModelGetZoneInside(impl.cm, &s->zone_inside, &s->zone_inside_overlap));
  s->max_nu = -1;
  for (const SceneBody &b : impl.bodies) s->max_nu = PetscMax(s->max_nu, b.nu);
  if (cp) PetscCall(ContactModelGetContactForce(impl.cm, -1, s->contact_force, &s->normal_force));
  s->bodies_zones = 0;
  for (const SceneZoneSpec &z : impl.zones) s->bodies_zones += z.zone.type == CONTACT_ZONE_BODIES ? 1 : 0;
  /* the reaction of every clamped or displaced face, and the loads they balance with the contact forces */
  {
    Vec                    u;
    PetscInt               total = 0;
    std::vector<PetscReal> reaction;
    for (const SceneBody &b : impl.bodies) total += (PetscInt)b.supports.size();
    PetscCallCXX(reaction.resize(3 * (size_t)total));
    PetscCall(ContactModelGetSolution(impl.cm, NULL, &u));
    PetscCall(FEMComputeReactions(impl.fem, feti, u, lambda, reaction.data()));
    s->nsupports = total;
    PetscInt k   = 0;
    for (size_t b = 0; b < impl.bodies.size(); b++) {
      const PetscReal origin[3] = {0, 0, 0};
      PetscReal       load[3];
      PetscCall(FEMComputeLoadResultant(impl.fem, (PetscInt)b, origin, load, NULL, NULL));
      for (int c = 0; c < 3; c++) s->applied_load[c] += load[c];
      for (const SceneSupport &sp : impl.bodies[b].supports) {
        for (int c = 0; c < 3; c++) s->reaction[c] += reaction[3 * k + c];
        if (k < CONTACTSCENE_MAX_SUPPORTS) {
          ContactSceneSupportForce &f = s->supports[k];
          f.body                      = (PetscInt)b;
          PetscCall(PetscStrncpy(f.option, sp.kind.c_str(), sizeof(f.option)));
          /* a selector too long for the field is shown by its tag (start and hash), as a contact zone's face */
          const std::string &shown = sp.selector.text.size() < sizeof(f.face) ? sp.selector.text : sp.selector.tag;
          PetscCall(PetscStrncpy(f.face, shown.c_str(), sizeof(f.face)));
          for (int c = 0; c < 3; c++) f.force[c] = reaction[3 * k + c];
        }
        k++;
      }
    }
  }
  /* the mechanical residuals, from u and lambda */
  PetscCall(ContactModelComputeResiduals(impl.cm, &s->residuals));
  s->contact_nodes = s->residuals.counts[0] + s->residuals.counts[1] + s->residuals.counts[2];
  {
    const ContactResiduals &r      = s->residuals;
    const PetscReal         all[8] = {r.equilibrium, r.gluing, r.penetration, r.normal_sign, r.complementarity, r.friction_cone, r.slip_rule, r.max};
    s->finite                      = PETSC_TRUE;
    for (PetscReal v : all)
      if (!std::isfinite((double)v)) s->finite = PETSC_FALSE;
  }
  s->converged = (st.converged && s->finite) ? PETSC_TRUE : PETSC_FALSE;
  if (s->finite) PetscCall(PetscStrncpy(s->reason, st.reason, sizeof(s->reason)));
  else {
    PetscCall(PetscSNPrintf(s->reason, sizeof(s->reason), "not converged: the residuals of the solution are not finite numbers (%s)", st.reason));
    PetscCall(PetscStrncpy(s->failed_check, ContactChecks[s->residuals.worst], sizeof(s->failed_check)));
  }
  PetscCall(PetscLogEventEnd(CONTACTSCENE_Summary, scene, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a number of the table in format, or NOT FINITE: the table never prints nan (docs/output.md) */
static std::string TableNumber(PetscReal v, const char *format)
{
  char buf[32];
  if (std::isfinite((double)v)) snprintf(buf, sizeof(buf), format, (double)v);
  else snprintf(buf, sizeof(buf), "NOT FINITE");
  return std::string(buf);
}

/*@C
  ContactSceneSummaryView - Print the summary as a human-readable table (the layout of the seed paper's tables, then the details).

  Collective

  Input Parameters:
+ s      - the summary
- viewer - an ASCII viewer (NULL: stdout of PETSC_COMM_WORLD)

  Level: beginner

.seealso: `ContactSceneSummaryViewJSON()`, `ContactSceneGetSummary()`
@*/
PetscErrorCode ContactSceneSummaryView(const ContactSceneSummary *s, PetscViewer viewer)
{
  const ContactResiduals &r = s->residuals;

  PetscFunctionBegin;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(PETSC_COMM_WORLD, &viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "scene \"%s\" on %d MPI process%s: %" PetscInt_FMT " subdomains, %" PetscInt_FMT " rigid modes\n", s->scene, (int)s->ranks, s->ranks > 1 ? "es" : "",
                                   s->subdomains, s->rigid_modes));
  PetscCall(PetscViewerASCIIPrintf(viewer, "pipeline: %s\n", s->description));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%10s %8s %6s %8s %8s %8s %8s %11s %10s %10s\n", "n", "m", "Iter", "n_A", "QPP", "QPQ", "other", "||F||", "setup [s]", "solve [s]"));
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "%10" PetscInt_FMT " %8" PetscInt_FMT " %6" PetscInt_FMT " %8" PetscInt_FMT " %8" PetscInt_FMT " %8" PetscInt_FMT " %8" PetscInt_FMT " %11.4e %10.3f %10.3f\n", s->n,
                                   s->m, s->iter, s->n_A, s->n_A_qpp, s->n_A_qpq, s->n_A_other, (double)s->norm_F, (double)s->time_setup, (double)s->time_solve));
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "multipliers: %" PetscInt_FMT " gluing + %" PetscInt_FMT " Dirichlet + %" PetscInt_FMT " normal + %" PetscInt_FMT " tangential; FETI primal dimension %" PetscInt_FMT
                                   "; ||F|| estimate: %" PetscInt_FMT " products (not in n_A)\n",
                                   s->m_gluing, s->m_dirichlet, s->m_normal, s->m_tangential, s->n_primal, s->n_A_estimate));
  {
    /* the setup time broken down by phase (those that ran), then the solve: where a long run spends it */
    std::string line = "times [s]:";
    for (int ph = 0; ph < CONEFETI_PHASE_COUNT; ph++) {
      char buf[64];
      if (!(s->time_phases[ph] > 0)) continue;
      std::string name = ConeFETIPhases[ph];
      std::replace(name.begin(), name.end(), '_', ' ');
      snprintf(buf, sizeof(buf), "%s%s %.3f", ph == CONEFETI_PHASE_SOLVE ? "; " : (line.back() == ':' ? " " : ", "), name.c_str(), (double)s->time_phases[ph]);
      line += buf;
    }
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s\n", line.c_str()));
  }
  if (s->pipeline != CONTACT_PIPELINE_LINEAR)
    PetscCall(PetscViewerASCIIPrintf(viewer, "contact nodes: %" PetscInt_FMT " = %" PetscInt_FMT " separated + %" PetscInt_FMT " stick + %" PetscInt_FMT " slip\n", s->contact_nodes, r.counts[0],
                                     r.counts[1], r.counts[2]));
  {
    auto        E    = [](PetscReal v) { return TableNumber(v, "%.1e"); };
    std::string line = "residuals (relative): equilibrium " + E(r.equilibrium) + ", gluing " + E(r.gluing);
    if (s->pipeline != CONTACT_PIPELINE_LINEAR)
      line += ", non-penetration " + E(r.penetration) + ", normal sign " + E(r.normal_sign) + ", complementarity " + E(r.complementarity) + ", friction cone " + E(r.friction_cone) + ", slip rule " +
              E(r.slip_rule);
    line += "; max " + E(r.max);
    if (s->acceptance > 0) line += " (acceptance " + E(s->acceptance) + ")";
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s\n", line.c_str()));
    if (s->pipeline == CONTACT_PIPELINE_COULOMB) PetscCall(PetscViewerASCIIPrintf(viewer, "Coulomb fixed point: |g - F l_n| / |F l_n| = %s\n", E(s->fixed_point).c_str()));
    if (s->friction_polygon && (s->pipeline == CONTACT_PIPELINE_TRESCA || s->pipeline == CONTACT_PIPELINE_COULOMB))
      PetscCall(PetscViewerASCIIPrintf(viewer,
                                       "friction polygon (-contact_friction_polygon %" PetscInt_FMT "): friction cone and slip rule above judge the polygon; against the friction disk it "
                                       "approximates, the solution's friction residual is %s (the approximation's own error, not in the verdict)\n",
                                       s->friction_polygon, E(r.approximation).c_str()));
  }
  {
    auto N = [](PetscReal v) { return TableNumber(v, "%.6e"); };
    auto V = [&N](const PetscReal v[3]) { return "(" + N(v[0]) + ", " + N(v[1]) + ", " + N(v[2]) + ")"; };
    if (s->pipeline != CONTACT_PIPELINE_LINEAR)
      PetscCall(PetscViewerASCIIPrintf(viewer, "contact force on the bodies: %s; sum of the normal forces %s\n", V(s->contact_force).c_str(), N(s->normal_force).c_str()));
    for (PetscInt k = 0; k < PetscMin(s->nsupports, (PetscInt)CONTACTSCENE_MAX_SUPPORTS); k++) {
      const ContactSceneSupportForce &f = s->supports[k];
      PetscCall(PetscViewerASCIIPrintf(viewer, "reaction of body %" PetscInt_FMT " %s %s: %s\n", f.body, f.option, f.face, V(f.force).c_str()));
    }
    if (s->nsupports > CONTACTSCENE_MAX_SUPPORTS)
      PetscCall(PetscViewerASCIIPrintf(viewer, "(%" PetscInt_FMT " more supports: only their sum below)\n", s->nsupports - (PetscInt)CONTACTSCENE_MAX_SUPPORTS));
    if (s->nsupports)
      PetscCall(PetscViewerASCIIPrintf(viewer, "forces on the bodies: reactions %s + loads %s%s\n", V(s->reaction).c_str(), V(s->applied_load).c_str(),
                                       s->pipeline == CONTACT_PIPELINE_LINEAR ? ""
                                       : s->bodies_zones ? " + the contact forces of the foundation zones (those between bodies act on both bodies and cancel; the contact force above "
                                                           "counts them on the zones' first bodies)"
                                                         : " + contact force above"));
  }
  if (s->unmatched_nodes)
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "note: %" PetscInt_FMT
                                     " slave nodes of zones between bodies have no point of the master face within the search distance and are not contact nodes (faces that overlap only in part, or "
                                     "a gap above -scene_zone<z>_search_distance; -scene_view shows them per zone)\n",
                                     s->unmatched_nodes));
  if (s->left_out_friction)
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "note: %" PetscInt_FMT " friction nodes of the contact faces are on rollers whose free components their contact normal leaves (or friction polygons are on), "
                                     "and are not contact nodes: they carry no contact force (docs/contact.md; on a symmetry plane, where the normal lies in the plane, friction nodes keep "
                                     "their contact and friction along the plane)\n",
                                     s->left_out_friction));
  if (s->left_out_overlapping)
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "note: %" PetscInt_FMT " nodes of the contact faces overlap the other side initially (by up to %g) but are not contact nodes (their Dirichlet conditions "
                                     "keep them out): the solution does not push them out\n",
                                     s->left_out_overlapping, (double)s->left_out_overlap));
  if (s->zone_inside >= 0)
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "note: every contact node of zone %" PetscInt_FMT " starts inside its obstacle (by %g at least), and the solution pushes them all out of it: "
                                     "a punch pressed in on purpose, or an obstacle on the body's side by mistake (a plane's -scene_zone%" PetscInt_FMT "_normal must point toward the body)\n",
                                     s->zone_inside, (double)s->zone_inside_overlap, s->zone_inside));
  /* P1 tetrahedra lock as nu -> 0.5: the displacements come out too small, and K_s and F get ill-conditioned
     (more products); the solve itself stays correct for the discrete problem */
  if (s->max_nu > 0.45)
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "note: Poisson's ratio %g is close to 0.5: linear tetrahedra lock for nearly incompressible material (displacements too small, "
                                     "stresses oscillate; refining helps only slowly) and the dual problem is ill-conditioned (more F products)\n",
                                     (double)s->max_nu));
  if (s->linear_option[0])
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "note: %s is an option of the linear FETI solve (-feti_ksp_*, -feti_pc_*), which a scene with contact does not run: its solve is "
                                     "preconditioned by -contact_pc_type and iterated by -contact_tao_*\n",
                                     s->linear_option));
  if (s->kplus_fallback)
    PetscCall(PetscViewerASCIIPrintf(
        viewer, "note: the explicit K+ blocks would not fit in memory; F products use the subdomain factors instead (slower products, same results; -feti_memory_budget, docs/feti.md)\n"));
  if (s->refinements)
    PetscCall(PetscViewerASCIIPrintf(viewer, "note: the solver's own test passed before the mechanical residuals did; %" PetscInt_FMT " tighter solve%s followed (the counts above include them)\n",
                                     s->refinements, s->refinements > 1 ? "s" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s: %s\n", s->converged ? "CONVERGED" : "NOT CONVERGED", s->reason));
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {

void AppendString(std::string &out, const char *s)
{
  out += '"';
  for (const char *p = s; *p; p++) {
    const unsigned char ch = (unsigned char)*p;
    if (ch == '"') out += "\\\"";
    else if (ch == '\\') out += "\\\\";
    else if (ch == '\n') out += "\\n";
    else if (ch == '\t') out += "\\t";
    else if (ch < 0x20) {
      char buf[8];
      snprintf(buf, sizeof(buf), "\\u%04x", ch);
      out += buf;
    } else out += (char)ch;
  }
  out += '"';
}

void Key(std::string &out, const char *key)
{
  if (out.size() > 1 && out.back() != '{') out += ',';
  AppendString(out, key);
  out += ':';
}

void Int(std::string &out, const char *key, PetscInt v)
{
  Key(out, key);
  out += std::to_string((long long)v);
}

void Real(std::string &out, const char *key, PetscReal v)
{
  char buf[64];
  Key(out, key);
  if (std::isfinite((double)v)) {
    snprintf(buf, sizeof(buf), "%.6e", (double)v);
    out += buf;
  } else out += "null"; /* JSON has no NaN or infinity */
}

void Str(std::string &out, const char *key, const char *v)
{
  Key(out, key);
  if (v) AppendString(out, v);
  else out += "null";
}

void Bool(std::string &out, const char *key, PetscBool v)
{
  Key(out, key);
  out += v ? "true" : "false";
}

} // namespace

/*@C
  ContactSceneSummaryToJSON - The summary as one line of JSON: an object whose first key is "conefeti" (the version).

  Not Collective

  Input Parameters:
+ s   - the summary
- len - size of json

  Output Parameter:
. json - the line (no newline)

  Notes:
  The fields are listed in docs/output.md. Non-finite numbers are written as null.

  Level: intermediate

.seealso: `ContactSceneSummaryViewJSON()`
@*/
PetscErrorCode ContactSceneSummaryToJSON(const ContactSceneSummary *s, char json[], size_t len)
{
  std::string             out = "{";
  const ContactResiduals &r   = s->residuals;
  char                    version[32];

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(version, sizeof(version), "%d.%d.%d", CONEFETI_VERSION_MAJOR, CONEFETI_VERSION_MINOR, CONEFETI_VERSION_PATCH));
  Str(out, "conefeti", version);
  Str(out, "scene", s->scene);
  Int(out, "ranks", s->ranks);
  Str(out, "pipeline", ContactPipelines[s->pipeline]);
  Str(out, "algorithm", s->pipeline == CONTACT_PIPELINE_COULOMB ? ContactCoulombAlgorithms[s->algorithm] : NULL);
  Str(out, "description", s->description);
  Bool(out, "converged", s->converged);
  Str(out, "reason", s->reason);
  Int(out, "n", s->n);
  Int(out, "n_primal", s->n_primal);
  Int(out, "m", s->m);
  Int(out, "m_gluing", s->m_gluing);
  Int(out, "m_dirichlet", s->m_dirichlet);
  Int(out, "m_normal", s->m_normal);
  Int(out, "m_tangential", s->m_tangential);
  Int(out, "subdomains", s->subdomains);
  Int(out, "rigid_modes", s->rigid_modes);
  Int(out, "iter", s->iter);
  Int(out, "al_iter", s->al_iter);
  Int(out, "n_A", s->n_A);
  Int(out, "n_A_qpp", s->n_A_qpp);
  Int(out, "n_A_qpq", s->n_A_qpq);
  Int(out, "n_A_other", s->n_A_other);
  Int(out, "n_A_estimate", s->n_A_estimate);
  Int(out, "coarse_solves", s->coarse_solves);
  Real(out, "norm_F", s->norm_F);
  Real(out, "time_setup", s->time_setup);
  Real(out, "time_solve", s->time_solve);
  Key(out, "time_phases");
  out += "{";
  for (int ph = 0; ph < CONEFETI_PHASE_COUNT; ph++) Real(out, ConeFETIPhases[ph], s->time_phases[ph]);
  out += "}";
  Int(out, "contact_nodes", s->contact_nodes);
  Int(out, "separated", r.counts[0]);
  Int(out, "stick", r.counts[1]);
  Int(out, "slip", r.counts[2]);
  Int(out, "unmatched_nodes", s->unmatched_nodes);
  Int(out, "left_out_friction", s->left_out_friction);
  Int(out, "left_out_overlapping", s->left_out_overlapping);
  Real(out, "left_out_overlap", s->left_out_overlap);
  Int(out, "zone_inside", s->zone_inside);
  Real(out, "zone_inside_overlap", s->zone_inside_overlap);
  Key(out, "contact_force");
  out += "[";
  for (int c = 0; c < 3; c++) {
    char buf[64];
    if (c) out += ",";
    snprintf(buf, sizeof(buf), "%.6e", (double)s->contact_force[c]);
    out += std::isfinite((double)s->contact_force[c]) ? buf : "null";
  }
  out += "]";
  Real(out, "normal_force", s->normal_force);
  {
    auto Vector = [&out](const char *key, const PetscReal v[3]) {
      Key(out, key);
      out += "[";
      for (int c = 0; c < 3; c++) {
        char buf[64];
        if (c) out += ",";
        snprintf(buf, sizeof(buf), "%.6e", (double)v[c]);
        out += std::isfinite((double)v[c]) ? buf : "null";
      }
      out += "]";
    };
    Key(out, "supports");
    out += "[";
    for (PetscInt k = 0; k < PetscMin(s->nsupports, (PetscInt)CONTACTSCENE_MAX_SUPPORTS); k++) {
      const ContactSceneSupportForce &f = s->supports[k];
      out += k ? ",{" : "{";
      Int(out, "body", f.body);
      Str(out, "option", f.option);
      Str(out, "face", f.face);
      Vector("force", f.force);
      out += "}";
    }
    out += "]";
    Int(out, "nsupports", s->nsupports);
    Vector("reaction", s->reaction);
    Vector("applied_load", s->applied_load);
  }
  Real(out, "acceptance", s->acceptance);
  Str(out, "failed_check", s->failed_check[0] ? s->failed_check : NULL);
  Int(out, "refinements", s->refinements);
  {
    char kplus[128];
    /* explicit and implicit as before auto existed (the pages made with -feti_kplus_explicit read them); auto says what it chose */
    if (s->kplus_fallback) PetscCall(PetscStrncpy(kplus, "implicit (memory)", sizeof(kplus)));
    else if (s->kplus_type == FETI_KPLUS_AUTO) PetscCall(PetscSNPrintf(kplus, sizeof(kplus), "auto: blocks in %" PetscInt_FMT " of %" PetscInt_FMT " subdomains", s->kplus_blocks, s->subdomains));
    else PetscCall(PetscStrncpy(kplus, s->kplus_explicit ? "explicit" : "implicit", sizeof(kplus)));
    Str(out, "kplus", kplus);
  }
  Int(out, "kplus_blocks", s->kplus_blocks);
  Str(out, "kplus_precision", FETIKplusPrecisions[s->kplus_precision]);
  Int(out, "kplus_single", s->kplus_single);
  Real(out, "kplus_factor_mb", s->kplus_factor_bytes / 1048576.0);
  Real(out, "kplus_factor_double_mb", s->kplus_factor_double_bytes / 1048576.0);
  Int(out, "friction_polygon", s->friction_polygon);
  Real(out, "fixed_point", s->fixed_point);
  Real(out, "feasibility", s->feasibility);
  Str(out, "fingerprint", s->fingerprint);
  Key(out, "residuals");
  out += "{";
  Real(out, "equilibrium", r.equilibrium);
  Real(out, "gluing", r.gluing);
  Real(out, "penetration", r.penetration);
  Real(out, "normal_sign", r.normal_sign);
  Real(out, "complementarity", r.complementarity);
  Real(out, "friction_cone", r.friction_cone);
  Real(out, "slip_rule", r.slip_rule);
  Real(out, "max", r.max);
  Real(out, "approximation", r.approximation);
  out += "}}";
  PetscCheck(out.size() < len, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "ContactSceneSummaryToJSON: the line needs %d characters, the buffer has %d", (int)out.size() + 1, (int)len);
  PetscCall(PetscStrncpy(json, out.c_str(), len));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneSummaryViewJSON - Print the summary as one JSON line (starting with {"conefeti":).

  Collective

  Input Parameters:
+ s      - the summary
- viewer - an ASCII viewer (NULL: stdout of PETSC_COMM_WORLD)

  Level: beginner

.seealso: `ContactSceneSummaryToJSON()`, `ContactSceneSummaryView()`
@*/
PetscErrorCode ContactSceneSummaryViewJSON(const ContactSceneSummary *s, PetscViewer viewer)
{
  char json[16384];

  PetscFunctionBegin;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(PETSC_COMM_WORLD, &viewer));
  PetscCall(ContactSceneSummaryToJSON(s, json, sizeof(json)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s\n", json));
  PetscFunctionReturn(PETSC_SUCCESS);
}
