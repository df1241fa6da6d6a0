/* ContactModel: contact zones on a FEM model -> constraint rows -> FETI -> ContactProblem -> primal
   recovery -> mechanical residuals and node states.

   Rows per contact node k (unit normal n of the node's body A, tangents t1, t2):
     N  u = n.(u_A - u_B) <= d_k   (foundation: u_B = 0, n and d_k from the obstacle's closest point, contactobstacle.cxx;
                                    between bodies: A is the slave node, u_B = sum_v w_v u(master node v) the displacement
                                    of its closest master point chi, n and d_k from chi - x, CollectBodiesZoneNodes())
     T1 u = t1.(u_A - u_B),  T2 u = t2.(u_A - u_B)   (only for Tresca and Coulomb nodes)
   or, with -contact_friction_polygon k, the k rows D_j u = d_j.(u_A - u_B), d_j = cos(j pi/k) t1 + sin(j pi/k) t2
   (contactpolygon.cxx)
   With the Lagrangian term l'(B u - c), l_n >= 0 is the contact force magnitude and -T'l_t the
   friction force on body A, so the slip rule reads: T u = 0 where |l_t| < g, and
   T u = s l_t with s >= 0 where |l_t| = g. Multipliers are nodal forces; stresses divide by the
   lumped nodal area of the contact face. */
#include <conefeti/private/contactmodelimpl.h>
#include <conefeti/private/reproduciblesum.h>
#include <conefeti/sys.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <tuple>

PetscClassId      CONTACTMODEL_CLASSID;
const char *const ContactZoneTypes[]    = {"foundation", "bodies", "ContactZoneType", "CONTACT_ZONE_", NULL};
const char *const ContactZoneSlaves[]   = {"finer", "body", "other", "ContactZoneSlave", "CONTACT_SLAVE_", NULL};
const char *const ContactNodeStatuses[] = {"separated", "stick", "slip", "ContactNodeStatus", "CONTACT_NODE_", NULL};

namespace {

/* scaled by the largest entry first: no overflow for |v| near the largest real, no underflow near the smallest */
void Normalize(PetscReal v[3])
{
  const PetscReal m = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
  if (!(m > 0)) return;
  for (int i = 0; i < 3; i++) v[i] /= m;
  const PetscReal s = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3; i++) v[i] /= s;
}

/* c = a x b */
void Cross(const PetscReal a[3], const PetscReal b[3], PetscReal c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* t1, t2 with (n, t1, t2) orthonormal, t1 built from the axis least aligned with n (deterministic) */
void Tangents(const PetscReal n[3], PetscReal t1[3], PetscReal t2[3])
{
  int axis = 0;
  for (int i = 1; i < 3; i++)
    if (std::fabs(n[i]) < std::fabs(n[axis])) axis = i;
  PetscReal e[3]    = {0, 0, 0};
  e[axis]           = 1;
  const PetscReal d = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
  for (int i = 0; i < 3; i++) t1[i] = e[i] - d * n[i];
  Normalize(t1);
  Cross(n, t1, t2);
}

/* The Dirichlet components of every node (global node -> mask of fixed components, bits 0-2). A node fixed in all
   the components its contact row would act on is left out of contact (its row would be a zero row of B); see
   CollectZoneNodes(). A node with a nonzero prescribed displacement (FEMSetDisplacement()) is marked fixed in all
   three components and kDirichletMoved, so it is left out whatever its law, also as a master node: a row that
   dropped a moved component would need the value in its gap, and a grip or punch face is not a contact face. */
const unsigned kDirichletMoved = 8u; /* DirichletNodes(): the node has a nonzero prescribed displacement */

PetscErrorCode DirichletNodes(FEM fem, std::map<PetscInt, unsigned> &fixed)
{
  IS                     is, all;
  PetscInt               n;
  const PetscInt        *idx;
  std::vector<PetscReal> values;

  PetscFunctionBegin;
  PetscCall(FEMGetGlobalDirichletDofs(fem, &is));
  PetscCall(ISAllGather(is, &all));
  PetscCall(ISGetLocalSize(all, &n));
  PetscCallCXX(values.resize(n));
  PetscCall(FEMGetDirichletValues(fem, all, values.data()));
  PetscCall(ISGetIndices(all, &idx));
  for (PetscInt i = 0; i < n; i++) PetscCallCXX(fixed[idx[i] / 3] |= values[i] != 0.0 ? 7u | kDirichletMoved : 1u << (idx[i] % 3));
  PetscCall(ISRestoreIndices(all, &idx));
  PetscCall(ISDestroy(&all));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A friction node on rollers: Dirichlet components (mask, none moved) at a node of a friction zone, as on the
   symmetry plane of a half or quarter model. Its rows drop the fixed components' terms, so its three rows act in the
   free components only. Where the normal lies in them (within kRollerNormal, below: the plane's normal is a tangent,
   as on a symmetry plane, whose mirror image is the model's other half) the node keeps its contact and friction:
   - one fixed component c: t2 = e_c, t1 = e_c x n. The t2 row is then a zero row (its only term is dropped), so
     its multiplier has a zero gradient and stays 0 in every solver: the friction disk acts as the interval
     |l_t1| <= g along the plane. The support takes any force along e_c, as the mirror half would.
   - two fixed components: the normal is along the free axis and both tangents are fixed: no tangential force can
     act (on the line where two symmetry planes meet it is 0 by symmetry), so the node is frictionless.
   Where the normal leaves the free components, a tangent row would repeat the normal one on the free components
   (both in the plane orthogonal to t1), and the node is left out (CountLeftOut() reports it). With friction
   polygons (-contact_friction_polygon) the polygon's directions would mix t2 into rows whose t1 part is the
   projection of the polygon, not its section, so such nodes are left out as well.
   The normal is projected into the free components first. Within kRollerNormal that is the mirror image's part:
   between bodies a node that touches its master surface takes the slave face's lumped normal, which on a symmetry
   plane averages only the model's side of a curved face and leans out of the plane by about h/(2R) (0.018 at the tip
   of the meshed half Hertz pair at h = 0.03 R); the mirror half would cancel exactly that. Obstacle normals and the
   directions chi(x) - x of a symmetric pair lie in the plane anyway. A roller face really inclined to the contact by
   less than that would see its gap scaled by at most 1/sqrt(1 - 0.1^2) (0.5%) and its slip across the roller
   direction ignored.
   Returns whether the node is kept; n, t1, t2 and the law are set only then. */
const PetscReal kRollerNormal = 0.1;

bool FrictionOnRollers(ContactNodeInfo &info, unsigned mask, PetscInt polygon)
{
  int nfixed = 0, fixedc = -1;
  if (polygon || (mask & kDirichletMoved)) return false;
  for (int c = 0; c < 3; c++)
    if (mask & (1u << c)) {
      nfixed++;
      fixedc = c;
      if (std::fabs(info.n[c]) > kRollerNormal) return false;
    }
  if (nfixed == 0 || nfixed == 3) return false;
  for (int c = 0; c < 3; c++)
    if (mask & (1u << c)) info.n[c] = 0;
  Normalize(info.n);
  if (nfixed == 2) {
    info.law  = CONTACT_FRICTIONLESS;
    info.coef = 0;
    Tangents(info.n, info.t1, info.t2);
    return true;
  }
  PetscReal e[3] = {0, 0, 0};
  e[fixedc]      = 1;
  Cross(e, info.n, info.t1);
  Normalize(info.t1);
  for (int c = 0; c < 3; c++) info.t2[c] = e[c];
  return true;
}

/* A face of a zone between bodies: its nodes (with lumped areas and outward normals) and triangles */
struct ZoneFace {
  PetscInt         body = -1, n = 0, ntri = 0, nb = 0, offset = 0;
  const char      *name  = nullptr;
  const PetscInt  *nodes = nullptr, *tri = nullptr;
  const PetscReal *areas = nullptr, *normals = nullptr, *X = nullptr;
  PetscReal        mean_edge = 0;
};

PetscErrorCode GetZoneFace(FEM fem, PetscInt body, const char *name, ZoneFace &f)
{
  PetscFunctionBegin;
  f.body = body;
  f.name = name;
  PetscCall(FEMGetTaggedNodes(fem, body, name, &f.n, &f.nodes, &f.areas, &f.normals));
  PetscCall(FEMGetTaggedTriangles(fem, body, name, &f.ntri, &f.tri));
  PetscCall(FEMGetBodyNodes(fem, body, &f.nb, &f.X));
  PetscCall(FEMGetBodyNodeOffset(fem, body, &f.offset));
  for (PetscInt t = 0; t < f.ntri; t++)
    for (int v = 0; v < 3; v++) {
      const PetscReal *p = &f.X[3 * f.tri[3 * t + v]], *q = &f.X[3 * f.tri[3 * t + (v + 1) % 3]];
      f.mean_edge += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    }
  if (f.ntri) f.mean_edge /= 3 * f.ntri;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Below this weight a master node is dropped from a row (and the others renormalized): a slave node on a master node
   or edge, up to the roundoff of its coordinates, gets exactly the node-to-node (or edge) row */
constexpr PetscReal kWeightDrop = 1e-12;
/* Where chi(x) and x are closer than this fraction of the master triangle's longest edge, the direction chi(x) - x is
   roundoff: the contact normal is the slave's outward normal */
constexpr PetscReal kNormalFromSlave = 1e-6;
/* A master point sideways of the slave face (chi(x) - x at more than 60 degrees from the slave's outward normal, e.g.
   beyond the edge of a smaller master face in the same plane) does not face the slave node: no contact node */
constexpr PetscReal kFacingCosine = 0.5;

/* The slave node x with outward normal ns, paired with the closest point of the master surface within the search
   distance: the contact normal, the gap and the master nodes with their weights. PETSC_FALSE when there is no such
   point, or it does not face the slave node (ContactZone, docs/contact.md "Contact between bodies"). */
PetscErrorCode PairSlaveNode(ContactSurfaceSearch &search, const ZoneFace &master, const PetscReal x[3], const PetscReal ns[3], PetscReal dsearch, PetscReal coincide, ContactNodeInfo &info,
                             PetscBool *paired)
{
  ContactSurfacePoint p;

  PetscFunctionBegin;
  *paired = PETSC_FALSE;
  PetscCall(search.Closest(x, dsearch, p));
  if (p.triangle < 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscReal d[3], hmax = 0;
  for (int c = 0; c < 3; c++) d[c] = p.chi[c] - x[c];
  for (int v = 0; v < 3; v++) {
    const PetscReal *a = &master.X[3 * master.tri[3 * p.triangle + v]], *b = &master.X[3 * master.tri[3 * p.triangle + (v + 1) % 3]];
    hmax = PetscMax(hmax, std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])));
  }
  if (p.dist <= coincide) {
    /* x on the master surface up to the roundoff of the coordinates (conforming meshes: coinciding nodes) */
    for (int c = 0; c < 3; c++) info.n[c] = ns[c];
    info.gap = 0;
  } else if (p.dist <= kNormalFromSlave * hmax) {
    for (int c = 0; c < 3; c++) info.n[c] = ns[c];
    info.gap = d[0] * ns[0] + d[1] * ns[1] + d[2] * ns[2];
  } else {
    /* n along chi - x, turned to the slave's outward side: against chi - x when x has passed into the master body
       (then the gap (chi - x).n is negative, an initial overlap) */
    const PetscReal s = (d[0] * ns[0] + d[1] * ns[1] + d[2] * ns[2]) / p.dist;
    if (PetscAbsReal(s) < kFacingCosine) PetscFunctionReturn(PETSC_SUCCESS);
    for (int c = 0; c < 3; c++) info.n[c] = (s > 0 ? 1 : -1) * d[c] / p.dist;
    info.gap = s > 0 ? p.dist : -p.dist;
  }
  Normalize(info.n);
  PetscReal sum = 0;
  info.nmaster  = 0;
  for (int v = 0; v < 3; v++)
    if (p.w[v] >= kWeightDrop) {
      info.master[info.nmaster] = master.tri[3 * p.triangle + v];
      info.weight[info.nmaster] = p.w[v];
      sum += p.w[v];
      info.nmaster++;
    }
  for (PetscInt v = 0; v < info.nmaster; v++) info.weight[v] /= sum;
  for (int c = 0; c < 3; c++) info.chi[c] = p.chi[c];
  *paired = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a node left out of contact for its Dirichlet conditions (mask: its components fixed, kDirichletMoved): counted when it
   has friction and fixed components that its normal does not lie beside (FrictionOnRollers(): a modelling limit, docs/contact.md)
   or when it overlaps initially, so that the summary can say what the solution does not see */
PetscErrorCode CountLeftOut(ContactModelData &d, PetscInt z, const ContactNodeInfo &info, unsigned mask)
{
  PetscFunctionBegin;
  if (info.law != CONTACT_FRICTIONLESS && (mask & 7u) != 7u && !(mask & kDirichletMoved)) {
    d.leftout_friction[z]++;
    for (int c = 0; c < 3; c++) /* how far the normal leaves the free components (-info: is it a symmetry plane's node?) */
      if (mask & (1u << c)) d.leftout_normal[z] = PetscMax(d.leftout_normal[z], PetscAbsReal(info.n[c]));
  }
  if (info.gap < 0) {
    d.leftout_overlapping[z]++;
    d.leftout_overlap[z] = PetscMax(d.leftout_overlap[z], -info.gap);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the nodes of a zone between bodies: every slave node that has a master point within the search distance */
PetscErrorCode CollectBodiesZoneNodes(ContactModel cm, PetscInt z, const std::map<PetscInt, unsigned> &fixed)
{
  ContactModelData    &d    = *cm->data;
  const ContactZone   &zone = d.zones[z];
  ZoneFace             A, B;
  ContactSurfaceSearch search;
  PetscReal            scale = 0;
  PetscInt             found = 0;

  PetscFunctionBegin;
  PetscCall(GetZoneFace(d.fem, zone.body, zone.face, A));
  PetscCall(GetZoneFace(d.fem, zone.other_body, zone.other_face, B));
  PetscCheck(A.n > 0, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONG, "contact zone %" PetscInt_FMT ": face '%s' of body %" PetscInt_FMT " has no node", z, zone.face, zone.body);
  PetscCheck(B.n > 0, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONG, "contact zone %" PetscInt_FMT ": face '%s' of body %" PetscInt_FMT " has no node", z, zone.other_face, zone.other_body);
  /* the finer face is the slave; on a tie (equal meshes up to roundoff) the zone's body */
  const PetscBool otherslave = zone.slave == CONTACT_SLAVE_OTHER || (zone.slave == CONTACT_SLAVE_FINER && B.mean_edge < (1 - 1e-6) * A.mean_edge) ? PETSC_TRUE : PETSC_FALSE;
  const ZoneFace &S = otherslave ? B : A, &M = otherslave ? A : B;
  PetscCall(search.SetUp(M.ntri, M.tri, M.X));
  const PetscReal dsearch = zone.search_distance > 0 ? zone.search_distance : search.longest_edge;
  d.slave[z]              = S.body;
  d.search[z]             = dsearch;
  /* coordinates that agree to this are the same point (the tolerance node-to-node matching had) */
  for (PetscInt i = 0; i < 3 * S.nb; i++) scale = PetscMax(scale, PetscAbsReal(S.X[i]));
  const PetscReal coincide = 1e-9 * PetscMax(scale, 1.0);
  for (PetscInt i = 0; i < S.n; i++) {
    ContactNodeInfo info;
    PetscBool       paired;
    info.zone = z;
    info.body = S.body;
    info.node = S.nodes[i];
    for (int c = 0; c < 3; c++) info.x[c] = S.X[3 * S.nodes[i] + c];
    info.area = S.areas[i];
    /* only the effects the scene calls for: friction with coefficient (or slip bound) 0 is no friction */
    info.law        = zone.coef == 0 ? CONTACT_FRICTIONLESS : zone.law;
    info.coef       = info.law == CONTACT_TRESCA ? zone.coef * S.areas[i] : zone.coef;
    info.other_body = M.body;
    PetscCall(PairSlaveNode(search, M, info.x, &S.normals[3 * i], dsearch, coincide, info, &paired));
    if (!paired) { /* no master point within the search distance (or none facing the node): not in contact */
      d.unmatched[z]++;
      continue;
    }
    found++;
    /* Dirichlet components of the slave node or its master nodes: where they are zero, u_c = 0 and the rows drop
       those terms and still say what they said, as foundation zones do: a slab clamped or on rollers next to the
       contact face keeps its contact, and so does a slave node whose master triangle reaches a clamped edge (a
       block pressed against the side of a clamped slab; before, such nodes were left out, and a zone made only of
       them stopped the setup). The node's own terms keep every row of it nonzero and independent of the other
       nodes' rows, so it is left out only when those terms go: when the slave node is fixed in all three
       components, when it has friction and fixed components that its normal does not lie beside
       (FrictionOnRollers(): on a symmetry plane it keeps its contact and friction), or when no term along the
       normal is left; and when the slave or a master node is moved (DirichletNodes(): a nonzero prescribed
       value). */
    {
      auto      f = fixed.find(S.offset + info.node);
      unsigned  mask[4];
      PetscBool held = PETSC_FALSE, along = PETSC_FALSE;
      bool      rollers = false;
      mask[0]           = f == fixed.end() ? 0u : f->second;
      for (PetscInt v = 0; v < info.nmaster; v++) {
        auto g      = fixed.find(M.offset + info.master[v]);
        mask[1 + v] = g == fixed.end() ? 0u : g->second;
      }
      if ((mask[0] & 7u) == 7u) held = PETSC_TRUE;
      for (PetscInt v = 0; v <= info.nmaster; v++)
        if (mask[v] & kDirichletMoved) held = PETSC_TRUE;
      if (!held && mask[0] && info.law != CONTACT_FRICTIONLESS) {
        rollers = FrictionOnRollers(info, mask[0], d.polygon);
        if (!rollers) held = PETSC_TRUE;
      }
      for (PetscInt v = 0; v <= info.nmaster; v++)
        for (int c = 0; c < 3; c++)
          if (!(mask[v] & (1u << c)) && info.n[c] != 0) along = PETSC_TRUE;
      if (held || !along) {
        PetscCall(CountLeftOut(d, z, info, mask[0]));
        continue;
      }
      info.fixed = mask[0];
      for (PetscInt v = 0; v < info.nmaster; v++) info.master_fixed[v] = mask[1 + v];
      if (!rollers) Tangents(info.n, info.t1, info.t2);
    }
    PetscCallCXX(d.nodes.push_back(info));
  }
  if (!found) {
    /* how far the master face is: the nearest of (at most 64 of) the slave nodes, by testing every triangle */
    PetscReal      nearest = PETSC_MAX_REAL;
    const PetscInt stride  = PetscMax(1, S.n / 64);
    for (PetscInt i = 0; i < S.n; i += stride) {
      ContactSurfacePoint p;
      PetscCall(search.Nearest(&S.X[3 * S.nodes[i]], p));
      nearest = PetscMin(nearest, p.dist);
    }
    SETERRQ(PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONG,
            "contact zone %" PetscInt_FMT ": none of the %" PetscInt_FMT " nodes of the slave face '%s' of body %" PetscInt_FMT " has a point of the master face '%s' of body %" PetscInt_FMT
            " within the search distance %g facing it (the master face is about %g away): check that the faces face each other (-scene_zone%" PetscInt_FMT "_face, _other_face), or raise the search "
            "distance above the gap (-scene_zone%" PetscInt_FMT "_search_distance; ContactZone search_distance)",
            z, S.n, S.name, S.body, M.name, M.body, (double)dsearch, (double)nearest, z, z);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CollectZoneNodes(ContactModel cm, PetscInt z, const std::map<PetscInt, unsigned> &fixed)
{
  ContactModelData  &d    = *cm->data;
  const ContactZone &zone = d.zones[z];
  PetscInt           n, offset;
  const PetscInt    *nodes;
  const PetscReal   *areas, *normals, *X;

  PetscFunctionBegin;
  if (zone.type == CONTACT_ZONE_BODIES) {
    PetscCall(CollectBodiesZoneNodes(cm, z, fixed));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(FEMGetTaggedNodes(d.fem, zone.body, zone.face, &n, &nodes, &areas, &normals));
  PetscCheck(n > 0, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONG, "contact zone %" PetscInt_FMT ": face '%s' of body %" PetscInt_FMT " has no node", z, zone.face, zone.body);
  PetscCall(FEMGetBodyNodes(d.fem, zone.body, NULL, &X));
  PetscCall(FEMGetBodyNodeOffset(d.fem, zone.body, &offset));
  for (PetscInt i = 0; i < n; i++) {
    ContactNodeInfo info;
    info.zone = z;
    info.body = zone.body;
    info.node = nodes[i];
    for (int c = 0; c < 3; c++) info.x[c] = X[3 * nodes[i] + c];
    info.area = areas[i];
    /* only the effects the scene calls for: friction with coefficient (or slip bound) 0 is no friction, so such
       a node gets no tangential rows and the zone runs the frictionless pipeline */
    info.law  = zone.coef == 0 ? CONTACT_FRICTIONLESS : zone.law;
    info.coef = info.law == CONTACT_TRESCA ? zone.coef * areas[i] : zone.coef;
    PetscCall(ContactObstacleNodeGeometry_Private(cm, z, info));
    /* A node with a Dirichlet component: u is zero there, so a frictionless row may drop that component's term
       and still say N u <= d (a node on a symmetry plane of a quarter model, where the obstacle's normal lies in
       the plane, keeps its contact). It is left out when every component its row acts on is fixed, and when it
       has friction and its normal does not lie in its free components (FrictionOnRollers(): on a symmetry plane
       a friction node keeps its contact, its friction along the plane); zones between bodies apply the same rule
       to the slave node and its master nodes (CollectBodiesZoneNodes()). */
    {
      auto      f       = fixed.find(offset + nodes[i]);
      PetscBool keep    = PETSC_TRUE;
      bool      rollers = false;
      if (f != fixed.end()) {
        keep = PETSC_FALSE;
        if (info.law != CONTACT_FRICTIONLESS) {
          rollers = FrictionOnRollers(info, f->second, d.polygon);
          keep    = rollers ? PETSC_TRUE : PETSC_FALSE;
        } else
          for (int c = 0; c < 3; c++)
            if (!(f->second & (1u << c)) && info.n[c] != 0) keep = PETSC_TRUE;
        info.fixed = f->second;
      }
      if (!keep) {
        PetscCall(CountLeftOut(d, z, info, f->second));
        continue;
      }
      if (!rollers) Tangents(info.n, info.t1, info.t2);
    }
    PetscCallCXX(d.nodes.push_back(info));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the directions of a node's rows: n, then t1, t2 (disks) or the friction polygon's d_j; only n when frictionless */
std::vector<std::array<PetscReal, 3>> RowDirections(const ContactModelData &d, const ContactNodeInfo &k)
{
  std::vector<std::array<PetscReal, 3>> dirs{{k.n[0], k.n[1], k.n[2]}};
  if (k.law == CONTACT_FRICTIONLESS) return dirs;
  if (!d.polygon) {
    dirs.push_back({k.t1[0], k.t1[1], k.t1[2]});
    dirs.push_back({k.t2[0], k.t2[1], k.t2[2]});
  } else
    for (PetscInt j = 0; j < d.polygon; j++) {
      PetscReal a[2];
      ContactPolygonDirection(d.polygon, j, a);
      dirs.push_back({a[0] * k.t1[0] + a[1] * k.t2[0], a[0] * k.t1[1] + a[1] * k.t2[1], a[0] * k.t1[2] + a[1] * k.t2[2]});
    }
  return dirs;
}

/* the FETI problem with the rows of all contact nodes in B, in node order (N, then T1, T2 or the polygon's rows);
   d.rows learns where each went */
PetscErrorCode CreateFETIWithContactRows(ContactModel cm)
{
  ContactModelData        &d = *cm->data;
  std::vector<FETIRowKind> kinds;
  std::vector<PetscInt>    rowptr{0}, body, node, comp;
  std::vector<PetscScalar> coef, rhs;

  PetscFunctionBegin;
  for (auto &k : d.nodes) {
    const auto dirs  = RowDirections(d, k);
    const int  nrows = (int)dirs.size();
    k.first_row      = (PetscInt)kinds.size();
    for (int r = 0; r < nrows; r++) {
      kinds.push_back(r == 0 ? FETI_ROW_CONTACT_NORMAL : FETI_ROW_CONTACT_TANGENTIAL);
      for (int c = 0; c < 3; c++) {
        if (!(k.fixed & (1u << c))) { /* u_c = 0 at a fixed node: the term carries nothing (CollectZoneNodes()) */
          body.push_back(k.body);
          node.push_back(k.node);
          comp.push_back(c);
          coef.push_back(dirs[r][c]);
        }
        for (PetscInt v = 0; v < k.nmaster; v++) {     /* u_slave - sum_v w_v u_master(v): the master point chi moves with its triangle */
          if (k.master_fixed[v] & (1u << c)) continue; /* u_c = 0 at that master node */
          body.push_back(k.other_body);
          node.push_back(k.master[v]);
          comp.push_back(c);
          coef.push_back(-k.weight[v] * dirs[r][c]);
        }
      }
      rowptr.push_back((PetscInt)body.size());
      rhs.push_back(r == 0 ? k.gap : 0.0);
    }
  }
  PetscCallCXX(d.rows.assign(kinds.size(), -1));
  PetscCall(FEMCreateFETIWithRows(d.fem, (PetscInt)kinds.size(), kinds.data(), rowptr.data(), body.data(), node.data(), comp.data(), coef.data(), rhs.data(), d.rows.data(), &d.feti));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the multipliers of the contact nodes this rank owns, and the ContactProblem */
PetscErrorCode BuildContactProblem(ContactModel cm)
{
  ContactModelData &d = *cm->data;
  PetscInt          rstart, rend;
  const PetscInt   *rows = d.rows.data();
  Mat               F, Q;
  Vec               h, e, lt;
  const char       *prefix;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(d.lambda, &rstart, &rend));
  for (size_t k = 0; k < d.nodes.size(); k++) {
    const PetscInt r = rows[d.nodes[k].first_row];
    if (r >= rstart && r < rend) PetscCallCXX(d.local.push_back((PetscInt)k));
  }
  /* the contact problem numbers its nodes law by law (ContactProblemAddNodes() below, once per law), and
     ContactProblemGetSlipBounds() answers in that order: the local nodes must come in the same order, or a
     scene whose zones mix laws would judge each node with another node's slip bound */
  PetscCallCXX(std::stable_sort(d.local.begin(), d.local.end(), [&d](PetscInt a, PetscInt b) { return d.nodes[a].law < d.nodes[b].law; }));
  for (PetscInt k : d.local) {
    const ContactNodeInfo &nd = d.nodes[k];
    const PetscInt         r  = rows[nd.first_row];
    PetscCallCXX(d.mult.push_back(r));
    for (PetscInt q = 1; q < d.stride; q++) PetscCallCXX(d.mult.push_back(nd.law == CONTACT_FRICTIONLESS ? -1 : rows[nd.first_row + q]));
    PetscCallCXX(d.lbody.push_back(nd.body));
    PetscCallCXX(d.lnode.push_back(nd.node));
    PetscCallCXX(d.lcoords.insert(d.lcoords.end(), {nd.x[0], nd.x[1], nd.x[2]}));
    PetscCallCXX(d.larea.push_back(nd.area));
  }
  PetscCall(FETIGetOperators(d.feti, &F, NULL, NULL, &Q));
  PetscCall(FETIGetRHS(d.feti, &h, &e));
  PetscCall(FETIGetParticularSolution(d.feti, &lt));
  PetscCall(ContactProblemCreate(PetscObjectComm((PetscObject)cm), &d.cp));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)cm, &prefix));
  PetscCall(ContactProblemSetOptionsPrefix(d.cp, prefix));
  PetscCall(ContactProblemSetOperator(d.cp, F, h));
  PetscCall(ContactProblemSetProjector(d.cp, Q, lt));
  for (ContactLaw law : {CONTACT_FRICTIONLESS, CONTACT_TRESCA, CONTACT_COULOMB}) {
    std::vector<PetscInt>  n, t1, t2, tang;
    std::vector<PetscReal> c;
    for (size_t j = 0; j < d.local.size(); j++) {
      const ContactNodeInfo &nd = d.nodes[d.local[j]];
      if (nd.law != law) continue;
      n.push_back(d.mult[d.stride * j]);
      t1.push_back(d.mult[d.stride * j + 1]);
      t2.push_back(d.mult[d.stride * j + 2]);
      tang.insert(tang.end(), d.mult.begin() + d.stride * j + 1, d.mult.begin() + d.stride * (j + 1));
      c.push_back(nd.coef);
    }
    if (d.polygon && law != CONTACT_FRICTIONLESS) PetscCall(ContactProblemAddPolygonNodes(d.cp, law, (PetscInt)n.size(), d.polygon, n.data(), tang.data(), c.data()));
    else PetscCall(ContactProblemAddNodes(d.cp, law, (PetscInt)n.size(), n.data(), t1.data(), t2.data(), c.data()));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

void ContactTangents_Private(const PetscReal n[3], PetscReal t1[3], PetscReal t2[3]) { Tangents(n, t1, t2); }

/*@C
  ContactModelCreate - A contact model on a finite element model (the FEM must be set up).

  Collective

  Input Parameter:
. fem - the model (referenced)

  Output Parameter:
. cm - the contact model

  Level: beginner

.seealso: `ContactModelAddZone()`, `ContactModelSetUp()`, `ContactModelSolve()`
@*/
PetscErrorCode ContactModelCreate(FEM fem, ContactModel *cm)
{
  ContactModel c;
  const char  *prefix;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscHeaderCreate(c, CONTACTMODEL_CLASSID, "ContactModel", "Contact on a finite element model", "Contact", PetscObjectComm((PetscObject)fem), ContactModelDestroy, ContactModelView));
  PetscCallCXX(c->data = new ContactModelData);
  PetscCall(PetscObjectReference((PetscObject)fem));
  c->data->fem = fem;
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)fem, &prefix));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)c, prefix));
  *cm = c;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelDestroy - Destroy a contact model.

  Collective

  Input Parameter:
. cm - the model

  Level: beginner

.seealso: `ContactModelCreate()`
@*/
PetscErrorCode ContactModelDestroy(ContactModel *cm)
{
  ContactModelData *d;

  PetscFunctionBegin;
  if (!*cm) PetscFunctionReturn(PETSC_SUCCESS);
  PetscValidHeaderSpecific(*cm, CONTACTMODEL_CLASSID, 1);
  if (--((PetscObject)(*cm))->refct > 0) {
    *cm = NULL;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  d = (*cm)->data;
  PetscCall(FEMDestroy(&d->fem));
  PetscCall(FETIDestroy(&d->feti));
  PetscCall(ContactProblemDestroy(&d->cp));
  PetscCall(VecDestroy(&d->lambda));
  PetscCall(VecDestroy(&d->u));
  PetscCall(VecDestroy(&d->alpha));
  delete d;
  PetscCall(PetscHeaderDestroy(cm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelAddZone - Add a contact zone (the same on every rank).

  Logically Collective

  Input Parameters:
+ cm   - the model
- zone - the zone (copied)

  Notes:
  Zones may share nodes (two zones that split a face share the line between them). Where two zones give a node
  the same row (the same partner, normal and gap), `ContactModelSetUp()` makes it one contact node of the first
  zone, with the area of both zones' triangles and their friction weighted by their areas; one triangle in two
  zones with different friction, and a Tresca zone next to a Coulomb zone, are errors.

  Level: beginner

.seealso: `ContactZone`, `ContactModelSetUp()`
@*/
PetscErrorCode ContactModelAddZone(ContactModel cm, const ContactZone *zone)
{
  PetscInt nbodies;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscCheck(!cm->data->setup, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONGSTATE, "ContactModelAddZone: add zones before ContactModelSetUp()");
  PetscCall(FEMGetNumBodies(cm->data->fem, &nbodies));
  PetscCheck(zone->type == CONTACT_ZONE_FOUNDATION || zone->type == CONTACT_ZONE_BODIES, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE,
             "contact zone: type %d is no ContactZoneType (CONTACT_ZONE_FOUNDATION or CONTACT_ZONE_BODIES)", (int)zone->type);
  PetscCheck(zone->law == CONTACT_FRICTIONLESS || zone->law == CONTACT_TRESCA || zone->law == CONTACT_COULOMB, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE,
             "contact zone: law %d is no ContactLaw (CONTACT_FRICTIONLESS, CONTACT_TRESCA or CONTACT_COULOMB)", (int)zone->law);
  PetscCheck(zone->body >= 0 && zone->body < nbodies, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE, "contact zone: body %" PetscInt_FMT " does not exist (%" PetscInt_FMT " bodies)",
             zone->body, nbodies);
  if (zone->type == CONTACT_ZONE_BODIES)
    PetscCheck(zone->other_body >= 0 && zone->other_body < nbodies && zone->other_body != zone->body, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE,
               "contact zone: the other body %" PetscInt_FMT " must exist and differ from body %" PetscInt_FMT, zone->other_body, zone->body);
  else PetscCall(ContactZoneCheckObstacle(zone));
  PetscCheck(zone->coef >= 0 && !PetscIsInfOrNanReal(zone->coef), PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE, "contact zone: invalid %s %g (must be finite and >= 0)",
             zone->law == CONTACT_TRESCA ? "slip bound" : "friction coefficient", (double)zone->coef);
  PetscCallCXX(cm->data->zones.push_back(*zone));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelSetFromOptions - Options of the model's FETI and contact solvers (read at setup).

  Collective

  Input Parameter:
. cm - the model

  Notes:
  The FETI options (-feti_*) and the contact options (-contact_*, see `ContactProblemSetFromOptions()`)
  are read when `ContactModelSetUp()` creates those objects.

  Level: beginner

.seealso: `ContactModelSetUp()`
@*/
PetscErrorCode ContactModelSetFromOptions(ContactModel cm)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  if (cm->data->cp) PetscCall(ContactProblemSetFromOptions(cm->data->cp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelSetUp - Build the contact rows, the FETI operators and the dual contact problem.

  Collective

  Input Parameter:
. cm - the model

  Options Database Key:
. -contact_friction_polygon <0> - k >= 2: replace each friction disk by a regular 2k-gon inscribed in it, with k tangential rows
                                  and k multipliers bounded by |m_j| <= sin(pi/(2k)) g (the approximate method of the seed paper's
                                  Table 3; `ContactProblemAddPolygonNodes()`); 0: the disks

  Notes:
  Only what the zones call for is built: no zone means no contact rows (the solve is then a linear
  FETI solve), frictionless zones add normal rows only, Tresca and Coulomb zones add tangential rows.

  Before FETI is set up, the rigid motions of the bodies that no Dirichlet condition and no contact row
  resists are sought (a body without support on a frictionless floor, a body touching its support along
  one node line, bodies that float together): if there is one, the setup stops with an error
  (`PETSC_ERR_NOT_CONVERGED`: a valid model without a unique solution, not bad input) that names the bodies and the motion, says whether the load works along it
  (no equilibrium: the force along it or the moment about its axis) or not (no unique displacement),
  and how to hold it. See docs/contact.md, "No equilibrium, or no unique answer".

  Level: beginner

.seealso: `ContactModelSolve()`, `ContactModelGetPipeline()`, `FEMComputeLoadResultant()`
@*/
PetscErrorCode ContactModelSetUp(ContactModel cm)
{
  ContactModelData            *d;
  std::map<PetscInt, unsigned> fixed;
  const char                  *prefix; /* the options the errors name are the user's, with the model's prefix */
  PetscBool                    set;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  if (d->setup) PetscFunctionReturn(PETSC_SUCCESS);
  PetscObjectOptionsBegin((PetscObject)cm);
  /* the contact problem reads it too (for its KKT residual): the same text, so that -help lists one meaning */
  PetscCall(PetscOptionsReal("-contact_acceptance_factor",
                             "Converged only when the KKT residual (ContactProblem) or every mechanical residual (ContactModel) is at most this times -contact_rtol (by default also at most 0.1, or "
                             "-contact_rtol if that is larger; a factor given is taken as given)",
                             "ContactModelSolve", d->acceptance_factor, &d->acceptance_factor, &set));
  if (set) d->acceptance_given = PETSC_TRUE; /* a later call without the option keeps it given */
  PetscCall(PetscOptionsInt("-contact_refine_max", "Tighter warm-started solves when the solver's test passes but a mechanical residual (or, with -contact_kkt_check, the KKT residual) does not",
                            "ContactModelSolve", d->refine_max, &d->refine_max, NULL));
  PetscCall(PetscOptionsInt("-contact_friction_polygon",
                            "Replace each friction disk by a regular 2k-gon inscribed in it, k tangential multipliers with simple bounds (the seed paper's Table 3; 0: disks)", "ContactModelSetUp",
                            d->polygon, &d->polygon, NULL));
  PetscOptionsEnd();
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)cm, &prefix));
  PetscCheck(d->polygon == 0 || (d->polygon >= 2 && d->polygon <= 64), PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE,
             "-%scontact_friction_polygon must be 0 (friction disks) or a number of directions between 2 and 64, got %" PetscInt_FMT, prefix ? prefix : "", d->polygon);
  d->stride = 1 + (d->polygon ? d->polygon : 2);
  PetscCheck(d->acceptance_factor >= 1 && d->acceptance_factor < PETSC_MAX_REAL, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE,
             "-%scontact_acceptance_factor must be finite and >= 1 (the residuals cannot be held below the solver's tolerance), got %g", prefix ? prefix : "", (double)d->acceptance_factor);
  PetscCheck(d->refine_max >= 0, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE, "-%scontact_refine_max must be >= 0, got %" PetscInt_FMT, prefix ? prefix : "", d->refine_max);
  PetscCall(ConeFETIProgressBegin_Private(d->progress, CONEFETI_PHASE_CONTACT_ROWS, 0));
  PetscCall(DirichletNodes(d->fem, fixed));
  PetscCallCXX(d->unmatched.assign(d->zones.size(), 0));
  PetscCallCXX(d->leftout_friction.assign(d->zones.size(), 0));
  PetscCallCXX(d->leftout_normal.assign(d->zones.size(), 0));
  PetscCallCXX(d->leftout_overlapping.assign(d->zones.size(), 0));
  PetscCallCXX(d->leftout_overlap.assign(d->zones.size(), 0));
  PetscCallCXX(d->slave.assign(d->zones.size(), -1));
  PetscCallCXX(d->search.assign(d->zones.size(), 0));
  for (PetscInt z = 0; z < (PetscInt)d->zones.size(); z++) {
    PetscCall(CollectZoneNodes(cm, z, fixed));
    if (d->unmatched[z])
      PetscCall(PetscInfo(cm, "contact zone %" PetscInt_FMT ": %" PetscInt_FMT " slave nodes have no master point within the search distance %g (not in contact)\n", z, d->unmatched[z],
                          (double)d->search[z]));
    if (d->leftout_friction[z] || d->leftout_overlapping[z])
      PetscCall(PetscInfo(cm,
                          "contact zone %" PetscInt_FMT ": left out for their Dirichlet conditions: %" PetscInt_FMT
                          " friction nodes on rollers their normal leaves (its fixed components up to %g), %" PetscInt_FMT " nodes that overlap by up to %g\n",
                          z, d->leftout_friction[z], (double)d->leftout_normal[z], d->leftout_overlapping[z], (double)d->leftout_overlap[z]));
  }
  PetscCheck(d->zones.empty() || !d->nodes.empty(), PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONG, "the contact zones have no admissible node (all held by Dirichlet conditions)");
  {
    PetscInt merged;
    PetscCall(ContactMergeSharedNodes_Private(cm, &merged));
    if (merged) PetscCall(PetscInfo(cm, "%" PetscInt_FMT " copies of contact nodes that two zones give the same row merged into their first zone's node\n", merged));
  }
  /* a rigid motion nothing resists would make the coarse matrix G G' singular (or nearly: garbage reported
     as converged); named here, before any factorization (contactrigidmotions.cxx) */
  {
    std::vector<FEMHoldingRow> holding;
    for (const ContactNodeInfo &k : d->nodes) {
      const auto dirs  = RowDirections(*d, k);
      const int  nrows = !(k.coef > 0) ? 1 : (int)dirs.size(); /* tangential rows with a zero bound carry no force */
      for (int r = 0; r < nrows; r++) {
        PetscReal dir[3];
        for (int c = 0; c < 3; c++) dir[c] = (k.fixed & (1u << c)) ? 0 : dirs[r][c]; /* the row as appended */
        FEMHoldingRow h{k.body, k.node, k.other_body, k.nmaster, {k.master[0], k.master[1], k.master[2]}, {k.weight[0], k.weight[1], k.weight[2]}, {dir[0], dir[1], dir[2]}};
        PetscCallCXX(holding.push_back(h));
      }
    }
    PetscCall(ContactCheckRigidMotions_Private(cm, d->fem, d->zones, holding));
  }
  PetscCall(CreateFETIWithContactRows(cm));
  /* contact needs hundreds of F products: a dense K+ block on the interface pays for its setup in time, but costs
     |b|^2 numbers beside the factor; auto gives it to the subdomains where it is no larger than the factor
     (-feti_kplus, -feti_kplus_memory_ratio; -feti_kplus_explicit 1 puts it everywhere, as before) */
  if (!d->zones.empty()) PetscCall(FETISetKplusType(d->feti, FETI_KPLUS_AUTO));
  /* the F products' triangular solves are bound by memory traffic: float copies of the block Cholesky factors
     halve it and the factors' memory; Iter stays and n_A moves within 2% on the brick from 10^3 to 10^6
     unknowns (docs/scale.md, lever (e)). They perturb F by about 1e-7 relative, which is also the floor of the
     mechanical residuals they reach: a tolerance below CONTACT_SINGLE_PRECISION_MIN_RTOL keeps the double
     factors (-feti_kplus_precision chooses either way) */
  if (!d->zones.empty()) {
    PetscReal rtol = CONTACT_DEFAULT_RTOL;
    PetscCall(PetscOptionsGetReal(((PetscObject)cm)->options, prefix, "-contact_rtol", &rtol, NULL));
    if (rtol >= CONTACT_SINGLE_PRECISION_MIN_RTOL) PetscCall(FETISetKplusPrecision(d->feti, FETI_KPLUS_PRECISION_SINGLE));
  }
  PetscCall(FETISetFromOptions(d->feti));
  PetscCall(ConeFETIProgressEnd_Private(d->progress));
  PetscCall(FETISetProgress(d->feti, d->progress.fn, d->progress.ctx));
  PetscCall(FETISetUp(d->feti));
  PetscCall(FETICreateVecs(d->feti, &d->u, &d->lambda, &d->alpha));
  if (!d->zones.empty()) {
    PetscCall(ConeFETIProgressBegin_Private(d->progress, CONEFETI_PHASE_CONTACT_PROBLEM, 0));
    PetscCall(BuildContactProblem(cm));
    PetscCall(ContactProblemSetProgress(d->cp, d->progress.fn, d->progress.ctx));
    d->cp->data->kkt_check      = PETSC_FALSE; /* the model judges by the mechanical residuals of u and lambda (ContactModelSolve()) */
    d->cp->data->refine_outside = PETSC_TRUE;  /* and runs the tighter solves itself, also for the KKT check when it is turned on */
    {
      /* contact solves need hundreds of F products whose count grows with the contact zone: FETI's Dirichlet
         preconditioner in face halves them at 10^6 unknowns and flattens their growth, for about one
         factor-based F product's reads per application (docs/scale.md, 'Why n_A grows: preconditioning'). Where
         most subdomains' F products use dense blocks (-feti_kplus auto chose them because they read at least
         -feti_kplus_speedup times less than the factor: large subdomains, few of them, as the paper's cubes),
         an application costs several F products and the products it saves do not pay for it (docs/scale.md,
         'The contact defaults'). -contact_pc_type chooses either way. */
      PC       pc;
      PetscInt nblocks, nsub;
      PetscCall(FETIGetKplusType(d->feti, NULL, &nblocks));
      PetscCall(FETIGetNumSubdomains(d->feti, &nsub, NULL, NULL));
      PetscCall(ContactProblemGetPC(d->cp, &pc));
      if (2 * nblocks <= nsub) PetscCall(PCSetType(pc, PCFETIDIRICHLET));
      PetscCall(PetscInfo(cm, "Preconditioner in face by default: %s (%" PetscInt_FMT " of %" PetscInt_FMT " subdomains use dense K+ blocks in F)\n", 2 * nblocks <= nsub ? "dirichlet" : "none",
                          nblocks, nsub));
    }
    PetscCall(ContactProblemSetFromOptions(d->cp));
    PetscCall(ContactProblemSetUp(d->cp));
    PetscCall(ContactProblemGetPipeline(d->cp, &d->pipeline));
    PetscCall(ConeFETIProgressEnd_Private(d->progress));
  } else d->pipeline = CONTACT_PIPELINE_LINEAR;
  d->setup = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {

/* The solver's relative tolerance: the contact problem's -contact_rtol, or the linear FETI solve's -feti_ksp_rtol */
PetscErrorCode GetSolverTolerance(ContactModel cm, PetscReal *rtol)
{
  ContactModelData &d = *cm->data;

  PetscFunctionBegin;
  if (d.cp) *rtol = d.cp->data->rtol;
  else {
    KSP ksp;
    PetscCall(FETIGetKSP(d.feti, &ksp));
    PetscCall(KSPGetTolerances(ksp, rtol, NULL, NULL, NULL));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The tolerances a solve starts with: the tighter solves scale them from these, and the solve ends with these exactly */
struct SolverTolerances {
  PetscReal rtol = 0, msa_rtol = 0, fixed_point_rtol = 0;
};

PetscErrorCode GetSolverTolerances(ContactModel cm, SolverTolerances &t)
{
  ContactModelData &d = *cm->data;

  PetscFunctionBegin;
  PetscCall(GetSolverTolerance(cm, &t.rtol));
  if (d.cp) {
    t.msa_rtol         = d.cp->data->msa_rtol;
    t.fixed_point_rtol = d.cp->data->fixed_point_rtol;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Set the solver's relative tolerance to rtol, the first ones t scaled with it: the contact problem's fixed-point
   tolerances when the user gave them; and the KKT check (-contact_kkt_check) of a tighter solve is held to the first
   solve's acceptance, as the mechanical residuals are (a tighter solve aims lower, it does not lower what is accepted) */
PetscErrorCode SetSolverTolerance(ContactModel cm, PetscReal rtol, const SolverTolerances &t)
{
  ContactModelData &d = *cm->data;

  PetscFunctionBegin;
  if (d.cp) {
    ContactProblemData &p     = *d.cp->data;
    const PetscBool     first = (PetscBool)(rtol == t.rtol);
    p.msa_rtol                = first ? t.msa_rtol : ContactScaledTolerance_Private(t.msa_rtol, rtol, t.rtol);
    p.fixed_point_rtol        = first ? t.fixed_point_rtol : ContactScaledTolerance_Private(t.fixed_point_rtol, rtol, t.rtol);
    p.acceptance_outside      = first ? 0 : ContactAcceptance_Private(p.acceptance_factor, p.acceptance_given, t.rtol);
    p.rtol                    = rtol;
    PetscCall(TaoSetTolerances(p.tao, 0.0, 0.0, rtol));
  } else {
    KSP ksp;
    PetscCall(FETIGetKSP(d.feti, &ksp));
    PetscCall(KSPSetTolerances(ksp, rtol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The solver's state as the user left it (its tolerances, whether the F products refine float factors, whether the
   contact solve recycles the previous multiplier), put back when ContactModelSolve() ends in an error: the tighter
   solves change them while they run and restore them at the end, which an error skips. A user who catches the error
   (PetscPushErrorHandler()) and solves again would otherwise solve at a tolerance other than the one set. A
   destructor cannot report an error of its own: restoring is tried, and the first error stands */
class ModelStateOnError {
public:
  explicit ModelStateOnError(ContactModel cm) : cm_(cm) {}
  PetscErrorCode Save()
  {
    ContactModelData &d = *cm_->data;

    PetscFunctionBegin;
    PetscCall(GetSolverTolerances(cm_, t_));
    PetscCall(FETIGetKplusRefine(d.feti, &refine_));
    if (d.cp) PetscCall(ContactProblemGetTao(d.cp, &tao_));
    if (tao_) PetscCall(TaoGetRecycleHistory(tao_, &recycle_));
    armed_ = true;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  void                    Disarm() { armed_ = false; }
  const SolverTolerances &Tolerances() const { return t_; }
  PetscBool               Refine() const { return refine_; }
  ~ModelStateOnError()
  {
    if (!armed_) return;
    (void)SetSolverTolerance(cm_, t_.rtol, t_);
    (void)FETISetKplusRefine(cm_->data->feti, refine_);
    if (tao_) (void)TaoSetRecycleHistory(tao_, recycle_);
  }

private:
  ContactModel     cm_;
  SolverTolerances t_;
  PetscBool        refine_ = PETSC_FALSE, recycle_ = PETSC_FALSE;
  Tao              tao_   = nullptr;
  bool             armed_ = false;
};

/* No load at all (f = 0, no prescribed displacement, no initial penetration): u = 0 and l = 0 satisfy every
   equation and inequality exactly, and no solver is needed (an iterative one would chase 0 relative to 0) */
PetscErrorCode WithoutLoad(ContactModel cm, PetscBool *none)
{
  ContactModelData  &d = *cm->data;
  Mat                B;
  Vec                c, f;
  const FETIRowKind *kinds;
  PetscReal          fmax;
  PetscInt           m, bad = 0;

  PetscFunctionBegin;
  PetscCall(FETIGetLoad(d.feti, &f));
  PetscCall(VecNorm(f, NORM_INFINITY, &fmax));
  PetscCall(FETIGetConstraints(d.feti, &B, &c, &kinds));
  if (c) {
    const PetscScalar *ca;
    PetscCall(VecGetLocalSize(c, &m));
    PetscCall(VecGetArrayRead(c, &ca));
    for (PetscInt i = 0; i < m; i++)
      if (ContactImposedValue_Private(kinds[i], PetscRealPart(ca[i])) != 0) bad = 1;
    PetscCall(VecRestoreArrayRead(c, &ca));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)cm)));
  *none = fmax == 0 && !bad ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The contact solve says "no equilibrium" when |G l - e| stagnates while its multiplier grows: the loads need more than
   supports and contact can carry. The model can check that claim: when the supports alone hold every body
   (FEMComputeFreeRigidMotions() without contact rows finds no free motion), G l = e is met by the gluing and support
   forces with no contact force at all, so an equilibrium exists and the stagnation is the solver's (with Coulomb
   friction: radii F l_n that lock the loop, e.g. F = 10 on the paper's brick with the merged algorithm). The
   reason then says that instead of a false statement about the mechanics. Otherwise it names the motion the load
   drives, and says when that motion proves the claim (contactrigidmotions.cxx). Computed only after such a verdict. */
PetscErrorCode CorrectNoEquilibrium(ContactModel cm)
{
  ContactModelData &d = *cm->data;
  Tao               tao;
  PetscBool         stagnated = PETSC_FALSE;
  PetscInt          nfree;
  const char       *prefix;
  char              cure[160];

  PetscFunctionBegin;
  /* only the solver's own sentence: a diagnosis in front of it (F not symmetric, Q no projector) is the real cause */
  if (!d.cp || !d.fem || std::strncmp(d.stats.reason, "no equilibrium", 14)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(ContactProblemGetTao(d.cp, &tao));
  PetscCall(TaoSMALXEGetStagnated(tao, &stagnated));
  if (!stagnated) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FEMComputeFreeRigidMotions(d.fem, 0, NULL, &nfree, NULL));
  if (nfree) {
    /* only contact holds some body: the claim may be true, and the growth of the multiplier says along which motion the
       load drives the bodies; the sentence gets it when it is a rigid motion the load works along */
    const char *lead = "; the multiplier grows along a rigid motion: ";
    std::string motion, brief, proof;
    size_t      len, room = 0;
    PetscCall(PetscStrlen(d.stats.reason, &len));
    /* room for the phrase, or for its short form (about 100 characters) */
    if (len + std::strlen(lead) + 120 < sizeof(d.stats.reason)) {
      room = sizeof(d.stats.reason) - 1 - len - std::strlen(lead);
      PetscCall(ContactDescribeStagnatedMotion_Private(cm, d.fem, d.feti, tao, d.alpha, d.u, room, motion, brief, proof));
    }
    if (!motion.empty() && motion.size() <= room) {
      std::string reason = d.stats.reason;
      if (!proof.empty()) {
        /* the motion proves that there is no equilibrium: the Coulomb sentence loses the other cause it gives (radii
           that lock the loop), and every sentence says why, with the motion's brief form when the whole one leaves no
           room for the proof */
        const char *found  = "no equilibrium found: ";
        std::string proven = reason;
        if (reason.rfind(found, 0) == 0) {
          PetscReal feasibility;
          char      buf[160];
          PetscCall(TaoSMALXEGetFeasibility(tao, &feasibility));
          PetscCall(PetscSNPrintf(buf, sizeof(buf), "no equilibrium: |G l - e| stagnates at %.3g while the multiplier grows; the loads exceed what supports and friction carry", (double)feasibility));
          proven = buf;
        }
        auto fits = [&](const std::string &m) { return (proven + lead + m + ", which proves it: " + proof).size() < sizeof(d.stats.reason); };
        if (fits(motion)) reason = proven;
        else if (fits(brief)) {
          reason = proven;
          motion = brief;
        } else proof.clear(); /* no room: the sentence as the solver gave it, with the motion */
      }
      const std::string whole = reason + lead + motion + (proof.empty() ? "" : ", which proves it: " + proof);
      PetscCall(PetscStrncpy(d.stats.reason, whole.c_str(), sizeof(d.stats.reason)));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)d.cp, &prefix));
  if (d.pipeline == CONTACT_PIPELINE_COULOMB)
    PetscCall(PetscSNPrintf(cure, sizeof(cure), "the Coulomb radii F l_n lock the loop (large F; try a smaller F or another -%scontact_coulomb_algorithm)", prefix ? prefix : ""));
  else PetscCall(PetscStrncpy(cure, "a limit of the solver", sizeof(cure)));
  PetscCall(PetscSNPrintf(d.stats.reason, sizeof(d.stats.reason),
                          "not converged: |G l - e| stagnates at %.3g while the multiplier grows, although the supports hold every body (an equilibrium exists): %s", (double)d.stats.feasibility,
                          cure));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One solve at the tolerance set: the linear FETI solve, or the contact pipeline (warm: from the current
   multipliers and the equality's multiplier of the previous solve), then the primal solution. */
PetscErrorCode SolveOnce(ContactModel cm, PetscBool warm, ContactStatistics *st)
{
  ContactModelData &d = *cm->data;

  PetscFunctionBegin;
  if (!d.cp) {
    KSP                ksp;
    KSPConvergedReason reason;
    PetscInt           its;
    PetscCall(FETISolveLinear(d.feti, d.lambda, d.u));
    PetscCall(FETIGetKSP(d.feti, &ksp));
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    PetscCall(KSPGetIterationNumber(ksp, &its));
    *st                  = ContactStatistics{};
    st->pipeline         = CONTACT_PIPELINE_LINEAR;
    st->converged        = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
    st->outer_iterations = its;
    st->al_iterations    = its;
    st->products_qpp     = its + 1;
    KSPType   type;
    PetscReal rtol;
    PetscCall(KSPGetType(ksp, &type));
    PetscCall(KSPGetTolerances(ksp, &rtol, NULL, NULL, NULL));
    /* a breakdown (or no convergence) at a tolerance near the rounding of the residual is the tolerance's, not the problem's;
       KSP mprgp and mpgp also break down when the exact residual stays above the tolerance the recurred one met */
    const char *why = "";
    if (reason < 0 && rtol < 1e-12) why = " (-feti_ksp_rtol below 1e-12: below what rounding lets the residual reach?)";
    else if (reason == KSP_DIVERGED_BREAKDOWN)
      why = " (rounding limits the accuracy: the exact residual stays above the tolerance; an ill-conditioned coarse problem? -info :feti gives its residual and condition estimate, "
            "-feti_coarse_refine more refinement steps)";
    PetscCall(PetscSNPrintf(st->reason, sizeof(st->reason), "linear FETI solve (KSP %s): %s in %" PetscInt_FMT " iterations%s", type ? type : "?", KSPConvergedReasons[reason], its, why));
  } else {
    Vec       w;
    Tao       tao;
    PetscBool recycle;
    PetscCall(ContactProblemGetTao(d.cp, &tao));
    PetscCall(TaoGetRecycleHistory(tao, &recycle));
    if (warm) PetscCall(TaoSetRecycleHistory(tao, PETSC_TRUE));
    else {
      /* start from the particular solution: G l = e holds from the first iterate (the inner solver
         projects it onto the set). (Starting from one carried by the gluing and Dirichlet rows alone, i.e.
         without contact forces, costs the brick more products.) */
      Vec lt;
      PetscCall(FETIGetParticularSolution(d.feti, &lt));
      PetscCall(VecCopy(lt, d.lambda));
    }
    PetscCall(ContactProblemSolve(d.cp, d.lambda));
    PetscCall(TaoSetRecycleHistory(tao, recycle));
    PetscCall(ContactProblemGetStatistics(d.cp, st));
    PetscCall(VecDuplicate(d.lambda, &w));
    PetscCall(ContactProblemGetEqualityMultiplier(d.cp, w));
    PetscCall(FETIComputeAlphaFromEquality(d.feti, w, d.alpha)); /* FETI owns the rigid-body amplitudes */
    PetscCall(VecDestroy(&w));
    PetscCall(FETIRecoverPrimal(d.feti, d.lambda, d.alpha, d.u));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/*@C
  ContactModelSolve - Solve, and accept the solution only if its mechanics says so: the linear FETI solve
  (no contact) or the contact pipeline, the rigid-body amplitudes and the primal solution, then the
  mechanical residuals of u and lambda (`ContactModelComputeResiduals()`) against the acceptance.

  Collective

  Input Parameter:
. cm - the model

  Options Database Keys:
+ -contact_acceptance_factor <10> - a solve converges only when every mechanical residual is at most this times the
                                    solver's relative tolerance (-contact_rtol, or -feti_ksp_rtol without contact); without
                                    the option also at most 0.1 (or the tolerance, if larger)
. -contact_refine_max <3>         - when the solver's own test passes but a residual does not, solve again from the
                                    current multipliers at a tighter tolerance, at most this many times
- -contact_kkt_check <false>      - also hold the KKT residual recomputed from the multipliers within the acceptance

  Notes:
  The solver stops on its own test (the projected gradient and |G l - e| relative to |P(h - F l~)|, which
  contains the gaps and the loads of the whole scene); the acceptance is by the mechanics of each body and zone.
  When they disagree, the tolerance is tightened in proportion to the excess (each time by a factor
  between 10 and 10^4, less where 1e-13 clamps it; when a solve at 1e-13 missed and -contact_refine_max allows one
  more, a last one goes below it, at most to 1e-15) and the solve continues warm, the equality's multiplier included.
  A tighter solve that stops before its own test (its iteration limit, a stall) is judged by the mechanics too and is
  the last, unless its residuals are not finite or -contact_kkt_check is on: then the solver's reason is the verdict.
  Such a solve below a relative tolerance of 1e-6 refines the F products where the subdomains' factors are
  stored in float (`FETISetKplusRefine()`): their perturbation of F, about 1e-7, would otherwise be its floor.
  The solver's tolerances, the refinement and a cold start are the user's again at the end, also when the solve
  ends in an error (a user who catches it can solve again).
  If the residuals are still above the acceptance after -contact_refine_max such solves, the solve has not
  converged, and `ContactModelGetStatistics()` says which check failed, where, and by how much.
  With -contact_kkt_check turned on (off in a model by default), the KKT residual recomputed from the multipliers
  must be within the same acceptance too: its failure also gets the tighter solves, and is the verdict (failed_check
  "dual_kkt" or "dual_equality") when it persists. These are the model's tighter solves: the ones `ContactProblemSolve()`
  runs for a problem used alone are off inside a model.
  A scene without load (no force, no prescribed displacement, no initial penetration) has the exact solution
  u = 0, l = 0, returned without a solve.

  alpha comes from the augmented Lagrangian's multiplier of G l = e, alpha = -(GG')^{-1} G w (`FETIComputeAlphaFromEquality()`) with
  w = G'mu (`ContactProblemGetEqualityMultiplier()`), then u = K+(f - B'l) + R alpha.

  Level: beginner

.seealso: `ContactModelGetSolution()`, `ContactModelComputeResiduals()`, `ContactModelGetStatistics()`
@*/
PetscErrorCode ContactModelSolve(ContactModel cm)
{
  ContactModelData *d;
  PetscBool         noload = PETSC_FALSE;
  PetscReal         rtol0, tol;
  PetscInt          nsingle;
  ModelStateOnError user(cm);
  ContactStatistics one = {};
  ContactResiduals  r;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscCall(ContactModelSetUp(cm));
  d        = cm->data;
  d->stats = ContactStatistics{};
  PetscCall(ConeFETIProgressBegin_Private(d->progress, CONEFETI_PHASE_SOLVE, 0));
  PetscCall(GetSolverTolerance(cm, &rtol0));
  d->stats.pipeline   = d->pipeline;
  d->stats.acceptance = ContactAcceptance_Private(d->acceptance_factor, d->acceptance_given, rtol0);
  if (d->cp) PetscCall(ContactProblemGetCoulombAlgorithm(d->cp, &d->stats.algorithm));
  PetscCall(WithoutLoad(cm, &noload));
  if (noload) {
    PetscCall(VecSet(d->lambda, 0.0));
    PetscCall(VecSet(d->u, 0.0));
    PetscCall(VecSet(d->alpha, 0.0));
    d->solved          = PETSC_TRUE;
    d->stats.converged = PETSC_TRUE;
    PetscCall(PetscStrncpy(d->stats.reason, "no load: u = 0 and l = 0 satisfy every equation and inequality exactly (no solve needed)", sizeof(d->stats.reason)));
    PetscCall(ConeFETIProgressEnd_Private(d->progress));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(user.Save());
  const SolverTolerances &first   = user.Tolerances();
  const PetscBool         refine0 = user.Refine();
  tol                             = rtol0;
  PetscCall(FETIGetKplusPrecision(d->feti, NULL, &nsingle, NULL, NULL));
  for (PetscInt round = 0;; round++) {
    /* float factors perturb F by about 1e-7 (relative), the floor of what a solve reaches with them: a tighter
       solve of a refinement round refines its F products to double accuracy (a scene whose gap dominates the
       right-hand side needs such rounds, and without this stops above the acceptance) */
    const PetscBool refine = (PetscBool)(refine0 || (round > 0 && nsingle > 0 && tol < CONTACT_SINGLE_PRECISION_MIN_RTOL));
    if (refine != refine0) PetscCall(PetscInfo(cm, "solve %" PetscInt_FMT " at relative tolerance %g: F products refine the float factors' solves\n", round, (double)tol));
    PetscCall(FETISetKplusRefine(d->feti, refine));
    PetscCall(SolveOnce(cm, round > 0 ? PETSC_TRUE : PETSC_FALSE, &one));
    ContactStatisticsAccumulate_Private(d->stats, one);
    d->stats.fixed_point = one.fixed_point;
    d->stats.feasibility = one.feasibility;
    d->solved            = PETSC_TRUE;
    PetscCall(ContactModelComputeResiduals(cm, &r));
    PetscCall(PetscInfo(cm, "solve %" PetscInt_FMT " at relative tolerance %g: %s; largest mechanical residual %g (%s), acceptance %g\n", round, (double)tol, one.reason, (double)r.max,
                        ContactChecks[r.worst], (double)d->stats.acceptance));
    /* with -contact_kkt_check on (a model turns it off: it judges by the mechanics), a solve whose own test passed
       but whose KKT residual recomputed from the multipliers did not is one more residual above the acceptance: it
       gets the tighter solves too, not the verdict of a solver that failed */
    const PetscBool kkt_failed = (PetscBool)(!one.converged && (!std::strcmp(one.failed_check, "dual_kkt") || !std::strcmp(one.failed_check, "dual_equality")));
    /* a tighter solve whose own test fails (its tolerance below what it can reach, or its iteration limit) is judged by
       the mechanics like any other: the first solve passed the test at -contact_rtol; it is the last one */
    const PetscBool stopped = (PetscBool)(round > 0 && !one.converged && !kkt_failed && !(d->cp && d->cp->data->kkt_check) && !PetscIsInfOrNanReal(r.max));
    if (!one.converged && !kkt_failed && !stopped) {
      d->stats.converged = PETSC_FALSE;
      PetscCall(PetscStrncpy(d->stats.failed_check, "solver", sizeof(d->stats.failed_check)));
      PetscCall(PetscStrncpy(d->stats.reason, one.reason, sizeof(d->stats.reason)));
      PetscCall(CorrectNoEquilibrium(cm));
      break;
    }
    if (!kkt_failed && r.max <= d->stats.acceptance) {
      d->stats.converged = PETSC_TRUE;
      if (round == 0) PetscCall(PetscStrncpy(d->stats.reason, one.reason, sizeof(d->stats.reason)));
      else if (stopped)
        PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason),
                                "every residual within the acceptance after %" PetscInt_FMT " tighter solve%s down to relative tolerance %.0e (the last stopped before its own test: %s)", round,
                                round > 1 ? "s" : "", (double)tol, one.reason));
      else
        PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason),
                                "%s, after %" PetscInt_FMT " tighter solve%s (down to relative tolerance %.0e) that brought the residuals within the acceptance", one.reason, round,
                                round > 1 ? "s" : "", (double)tol));
      break;
    }
    if (round >= d->refine_max || tol < CONTACT_REFINE_TIGHTEST || stopped) {
      char what[200];
      d->stats.converged = PETSC_FALSE;
      if (kkt_failed) { /* the check the user asked for failed: it is the verdict, with the mechanics' worst beside it */
        char tail[160], mechanics[96] = "";
        if (r.max > d->stats.acceptance) PetscCall(PetscSNPrintf(mechanics, sizeof(mechanics), "; mechanics: %s %.1e", ContactChecks[r.worst], (double)r.max));
        PetscCall(PetscSNPrintf(tail, sizeof(tail), "%s, after %" PetscInt_FMT " solve%s down to relative tolerance %.0e", mechanics, round + 1, round ? "s" : "", (double)tol));
        /* the solver's reason shortened so that the tail is never cut */
        std::string why = std::string(one.reason).substr(0, sizeof(d->stats.reason) - 1 - std::strlen(tail)) + tail;
        PetscCall(PetscStrncpy(d->stats.failed_check, one.failed_check, sizeof(d->stats.failed_check)));
        PetscCall(PetscStrncpy(d->stats.reason, why.c_str(), sizeof(d->stats.reason)));
        break;
      }
      PetscCall(PetscStrncpy(d->stats.failed_check, ContactChecks[r.worst], sizeof(d->stats.failed_check)));
      PetscCall(ContactResidualsDescribe_Private(&r, r.worst, what, sizeof(what)));
      if (stopped)
        PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason),
                                "%s, above the acceptance %.1e, after %" PetscInt_FMT " solves down to relative tolerance %.0e (the last stopped before its own test: %s)", what,
                                (double)d->stats.acceptance, round + 1, (double)tol, one.reason));
      else
        PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason),
                                "%s, above the acceptance %.1e, after %" PetscInt_FMT " solve%s down to relative tolerance %.0e (the solver's own test passed)", what, (double)d->stats.acceptance,
                                round + 1, round ? "s" : "", (double)tol));
      break;
    }
    d->stats.refinements++;
    {
      PetscReal worst = r.max;
      if (kkt_failed) { /* the KKT residual's excess sets the tightening too */
        PetscReal natural, equality;
        PetscCall(ContactProblemComputeKKTResidual(d->cp, d->lambda, &natural, &equality));
        d->stats.products_other += 2;
        worst = PetscMax(worst, PetscMax(natural, equality));
      }
      /* not below 1e-13, but for one last solve when a solve at 1e-13 missed: the solver's tolerance is relative to
         |P(h - F l~)|, which holds every gap of the scene, and a gap far larger than the displacements (an obstacle a
         thousand times the body's size away) can leave 1e-13 of it above what the displacements need (contactimpl.h) */
      tol = ContactTighterTolerance_Private(tol, d->stats.acceptance, worst);
    }
    PetscCall(SetSolverTolerance(cm, tol, first));
  }
  if (tol != rtol0) PetscCall(SetSolverTolerance(cm, rtol0, first));
  PetscCall(FETISetKplusRefine(d->feti, refine0));
  user.Disarm(); /* the user's state is back */
  PetscCall(ConeFETIProgressEnd_Private(d->progress));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelSetProgress - A hook told how the setup and the solve progress: contact rows, every phase of
  `FETISetUp()` (subdomains counted), the contact problem, then the solve with each outer iteration.

  Logically Collective

  Input Parameters:
+ cm  - the model (before `ContactModelSetUp()`)
. fn  - the hook (NULL: none)
- ctx - its context

  Notes:
  Passed on to the model's FETI problem (`FETISetProgress()`) and contact problem (`ContactProblemSetProgress()`).
  The library prints nothing; see `ConeFETIProgressFn`.

  Level: intermediate

.seealso: `ConeFETIProgressFn`, `ContactSceneSetProgress()`, `FETISetProgress()`, `ContactProblemSetProgress()`
@*/
PetscErrorCode ContactModelSetProgress(ContactModel cm, ConeFETIProgressFn fn, void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  cm->data->progress.fn  = fn;
  cm->data->progress.ctx = ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetFETI - The model's FETI problem (after setup).

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameter:
. feti - the FETI problem (do not destroy)

  Level: intermediate

.seealso: `ContactModelSetUp()`
@*/
PetscErrorCode ContactModelGetFETI(ContactModel cm, FETI *feti)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscCheck(cm->data->setup, PETSC_COMM_SELF, PETSC_ERR_ORDER, "ContactModelGetFETI: call ContactModelSetUp() first (it creates the FETI problem)");
  *feti = cm->data->feti;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetContactProblem - The dual contact problem (NULL without contact zones).

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameter:
. cp - the problem (do not destroy)

  Level: intermediate

.seealso: `ContactProblem`
@*/
PetscErrorCode ContactModelGetContactProblem(ContactModel cm, ContactProblem *cp)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  *cp = cm->data->cp;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetPipeline - The pipeline the zones call for (after setup).

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameter:
. pipeline - linear (no zone), frictionless, tresca or coulomb

  Level: beginner

.seealso: `ContactPipeline`
@*/
PetscErrorCode ContactModelGetPipeline(ContactModel cm, ContactPipeline *pipeline)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  *pipeline = cm->data->pipeline;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetSolution - The multipliers and the primal solution (after a solve).

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameters:
+ lambda - dual vector (do not destroy), or NULL
- u      - primal vector, subdomain copies concatenated (do not destroy), or NULL

  Level: beginner

.seealso: `ContactModelSolve()`, `FEMPrimalToGlobal()`
@*/
PetscErrorCode ContactModelGetSolution(ContactModel cm, Vec *lambda, Vec *u)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscCheck(cm->data->solved, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONGSTATE, "ContactModel: solve first");
  if (lambda) *lambda = cm->data->lambda;
  if (u) *u = cm->data->u;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetStatistics - Iterations and Hessian products of the last `ContactModelSolve()` (summed over its
  solves when it tightened the tolerance), and its verdict: converged only when the solver's test passed and every
  mechanical residual is within the acceptance; otherwise failed_check and reason say what failed, where and by how much.

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameter:
. stats - the statistics (for the linear pipeline: CG iterations as outer iterations, F products as QPP)

  Level: beginner

.seealso: `ContactStatistics`
@*/
PetscErrorCode ContactModelGetStatistics(ContactModel cm, ContactStatistics *stats)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  *stats = cm->data->stats;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetUnmatchedNodes - The number of slave nodes of the zones between bodies that have no point of the master
  face within the search distance (or none facing them), and so are not contact nodes.

  Not Collective (the same on every rank)

  Input Parameter:
. cm - the model (set up)

  Output Parameter:
. n - the number, summed over the zones (0 when every slave node lies over the master face)

  Notes:
  Each slave node x is paired with the closest point of the master face (`ContactZone`, `ContactZoneSlave`). A slave face
  larger than the master face has such nodes by design (beyond the master's edge; their closest master point lies
  sideways); a nonzero count on faces meant to touch all over says they do not (shifted bodies, an initial gap above
  the search distance, the `search_distance` of `ContactZone`). A zone none of whose slave nodes has a master point
  within the search distance is an error at `ContactModelSetUp()`. The conefeti driver prints a note when the count is
  nonzero; `ContactModelView()` gives it per zone.

  Level: intermediate

.seealso: `ContactModelAddZone()`, `ContactModelView()`, `ContactZone`
@*/
PetscErrorCode ContactModelGetUnmatchedNodes(ContactModel cm, PetscInt *n)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscValidIntPointer(n, 2);
  PetscCheck(cm->data->setup, PetscObjectComm((PetscObject)cm), PETSC_ERR_ORDER, "Call ContactModelSetUp() first");
  *n = 0;
  for (PetscInt u : cm->data->unmatched) *n += u;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetLeftOutNodes - The nodes of the contact faces that their Dirichlet conditions keep out of contact and
  that the solution may therefore not see: friction nodes on rollers whose normal leaves the free components, and
  nodes that overlap initially.

  Not Collective

  Input Parameter:
. cm - the model (set up)

  Output Parameters:
+ nfriction   - friction nodes (Tresca, Coulomb) with one or two fixed components whose contact normal does not lie in
                the free ones (more than 0.1 out of them); NULL if not needed
. noverlap    - nodes left out for any Dirichlet condition (clamped, such rollers, moved) whose initial gap is
                negative; NULL if not needed
- overlap     - the largest initial overlap (-gap) among those, 0 when there is none; NULL if not needed

  Notes:
  A contact row acts on the node's displacement along its normal and, with friction, along two tangents. Where a
  component is fixed (u = 0) its term is dropped. A frictionless row keeps the node as long as a free component
  lies along the normal. A friction node keeps its contact and friction where its normal lies in its free components,
  as on the symmetry plane of a half or quarter model: with one fixed component c its tangents are e_c x n and e_c,
  the second row is a zero row whose multiplier stays 0, so friction acts along the plane only (the mirror half,
  or the support, takes any force along e_c); with two fixed components no tangent is free and the node is
  frictionless. Where the normal leaves the free components, a tangent would repeat the normal row on them, and the
  node is left out (docs/contact.md, "What is still left out, and said"): it carries no contact force, and an
  obstacle that overlaps only such nodes leaves the scene without load. The conefeti driver prints a note when
  either count is nonzero.

  Level: intermediate

.seealso: `ContactModelGetUnmatchedNodes()`, `ContactModelSetUp()`
@*/
PetscErrorCode ContactModelGetLeftOutNodes(ContactModel cm, PetscInt *nfriction, PetscInt *noverlap, PetscReal *overlap)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscCheck(cm->data->setup, PetscObjectComm((PetscObject)cm), PETSC_ERR_ORDER, "Call ContactModelSetUp() first");
  if (nfriction) *nfriction = 0;
  if (noverlap) *noverlap = 0;
  if (overlap) *overlap = 0;
  for (size_t z = 0; z < cm->data->zones.size(); z++) {
    if (nfriction) *nfriction += cm->data->leftout_friction[z];
    if (noverlap) *noverlap += cm->data->leftout_overlapping[z];
    if (overlap) *overlap = PetscMax(*overlap, cm->data->leftout_overlap[z]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetZoneInside - The first foundation zone whose every contact node starts inside its obstacle.

  Not Collective

  Input Parameter:
. cm - the model (set up)

  Output Parameters:
+ zone    - that zone, -1 when every foundation zone has a node outside its obstacle (or on its surface)
- overlap - the smallest initial overlap (-gap) of the zone's nodes, 0 when zone is -1; NULL if not needed

  Notes:
  The solution pushes every node of such a zone out of the obstacle by at least its overlap. That is a flat punch
  pressed into a face on purpose, or an obstacle on the body's side by mistake: a plane whose normal points away
  from the body instead of toward it, a sphere or cylinder that holds the face. The conefeti driver prints a note.

  Level: intermediate

.seealso: `ContactModelGetNodeGeometry()`, `ContactModelGetLeftOutNodes()`
@*/
PetscErrorCode ContactModelGetZoneInside(ContactModel cm, PetscInt *zone, PetscReal *overlap)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscValidIntPointer(zone, 2);
  PetscCheck(cm->data->setup, PetscObjectComm((PetscObject)cm), PETSC_ERR_ORDER, "Call ContactModelSetUp() first");
  *zone = -1;
  if (overlap) *overlap = 0;
  /* the nodes are the same on every rank: the same answer everywhere, no communication */
  const std::vector<ContactNodeInfo> &nodes = cm->data->nodes;
  for (PetscInt z = 0; z < (PetscInt)cm->data->zones.size() && *zone < 0; z++) {
    PetscInt  count    = 0;
    PetscBool inside   = PETSC_TRUE;
    PetscReal smallest = PETSC_MAX_REAL;
    for (const ContactNodeInfo &nd : nodes) {
      if (nd.zone != z || nd.other_body >= 0) continue;
      count++;
      if (!(nd.gap < 0)) inside = PETSC_FALSE;
      else smallest = PetscMin(smallest, -nd.gap);
    }
    if (count && inside) {
      *zone = z;
      if (overlap) *overlap = smallest;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetNodes - The contact nodes whose multipliers this rank owns.

  Not Collective

  Input Parameter:
. cm - the model (set up)

  Output Parameters:
+ n      - number of local contact nodes
. body   - body of each
. node   - body node id of each
. coords - 3 coordinates per node
- area   - lumped nodal area of the contact face at each

  Level: intermediate

.seealso: `ContactModelGetNodeStates()`
@*/
PetscErrorCode ContactModelGetNodes(ContactModel cm, PetscInt *n, const PetscInt **body, const PetscInt **node, const PetscReal **coords, const PetscReal **area)
{
  ContactModelData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  PetscCheck(d->setup, PETSC_COMM_SELF, PETSC_ERR_ORDER, "ContactModelGetNodes: call ContactModelSetUp() first (it finds the contact nodes)");
  if (n) *n = (PetscInt)d->local.size();
  if (body) *body = d->lbody.data();
  if (node) *node = d->lnode.data();
  if (coords) *coords = d->lcoords.data();
  if (area) *area = d->larea.data();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetNodeGeometry - The contact normal and the initial gap of this rank's contact nodes (order of
  `ContactModelGetNodes()`).

  Not Collective

  Input Parameter:
. cm - the model (set up)

  Output Parameters (either may be NULL):
+ normal - 3 per node: the unit normal n of the node's rows, the node's body's outward direction (foundation zones:
           into the obstacle, `ContactZoneComputeGap()`; zones between bodies: from the slave node toward its master
           point, see `ContactZone`)
- gap    - per node: the initial gap d of its row N u <= d (negative: an initial overlap)

  Level: intermediate

.seealso: `ContactModelGetNodes()`, `ContactZoneComputeGap()`
@*/
PetscErrorCode ContactModelGetNodeGeometry(ContactModel cm, PetscReal normal[], PetscReal gap[])
{
  ContactModelData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  PetscCheck(d->setup, PetscObjectComm((PetscObject)cm), PETSC_ERR_ORDER, "Call ContactModelSetUp() first");
  for (size_t j = 0; j < d->local.size(); j++) {
    const ContactNodeInfo &nd = d->nodes[d->local[j]];
    if (gap) gap[j] = nd.gap;
    if (normal)
      for (int c = 0; c < 3; c++) normal[3 * j + c] = nd.n[c];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetNodePartners - What this rank's contact nodes (order of `ContactModelGetNodes()`) are paired with: in a
  zone between bodies, the master point chi of the slave node and the master nodes whose displacements its rows
  interpolate.

  Not Collective

  Input Parameter:
. cm - the model (set up)

  Output Parameters (any may be NULL):
+ body    - per node: the master body (-1 for a foundation zone)
. nodes   - 3 per node: the master body's node ids, -1 where unused (a master vertex has one, an edge two, a triangle three)
. weights - 3 per node: their weights (each >= 1e-12, summing to 1; 0 where unused)
- point   - 3 per node: the master point chi (a foundation zone: the obstacle's closest point, x + gap n)

  Notes:
  The rows of node k act on u(k) - sum_v weights[v] u(nodes[v]). On conforming meshes every slave node has one master
  node, at its own position, with weight 1: node to node.

  Level: intermediate

.seealso: `ContactModelGetNodes()`, `ContactModelGetNodeGeometry()`, `ContactZone`
@*/
PetscErrorCode ContactModelGetNodePartners(ContactModel cm, PetscInt body[], PetscInt nodes[], PetscReal weights[], PetscReal point[])
{
  ContactModelData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  PetscCheck(d->setup, PetscObjectComm((PetscObject)cm), PETSC_ERR_ORDER, "Call ContactModelSetUp() first");
  for (size_t j = 0; j < d->local.size(); j++) {
    const ContactNodeInfo &nd = d->nodes[d->local[j]];
    if (body) body[j] = nd.other_body;
    for (int v = 0; v < 3; v++) {
      if (nodes) nodes[3 * j + v] = v < nd.nmaster ? nd.master[v] : -1;
      if (weights) weights[3 * j + v] = v < nd.nmaster ? nd.weight[v] : 0;
      if (point) point[3 * j + v] = nd.other_body >= 0 ? nd.chi[v] : nd.x[v] + nd.gap * nd.n[v];
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelView - Describe the model: zones, contact nodes per law, the pipeline, FETI and the contact solver.

  Collective

  Input Parameters:
+ cm     - the model
- viewer - an ASCII viewer (or NULL)

  Level: beginner

.seealso: `ContactModelSolve()`
@*/
PetscErrorCode ContactModelView(ContactModel cm, PetscViewer viewer)
{
  ContactModelData *d;
  PetscBool         iascii;
  PetscInt          counts[3] = {0, 0, 0};

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(PetscObjectComm((PetscObject)cm), &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(PETSC_SUCCESS);
  for (auto &n : d->nodes) counts[n.law]++;
  PetscCall(PetscObjectPrintClassNamePrefixType((PetscObject)cm, viewer));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%zu contact zones; contact nodes: %" PetscInt_FMT " frictionless, %" PetscInt_FMT " Tresca, %" PetscInt_FMT " Coulomb; pipeline %s\n", d->zones.size(),
                                   counts[0], counts[1], counts[2], ContactPipelines[d->pipeline]));
  for (size_t z = 0; z < d->zones.size(); z++) {
    const ContactZone &zn = d->zones[z];
    if (zn.type == CONTACT_ZONE_FOUNDATION && zn.shape == CONTACT_OBSTACLE_SPHERE)
      PetscCall(PetscViewerASCIIPrintf(viewer, "zone %zu: body %" PetscInt_FMT " face %s on a rigid sphere with center (%g, %g, %g) and radius %g, %s %g\n", z, zn.body, zn.face, (double)zn.center[0],
                                       (double)zn.center[1], (double)zn.center[2], (double)zn.radius, ContactLaws[zn.law], (double)zn.coef));
    else if (zn.type == CONTACT_ZONE_FOUNDATION && zn.shape == CONTACT_OBSTACLE_CYLINDER)
      PetscCall(PetscViewerASCIIPrintf(viewer, "zone %zu: body %" PetscInt_FMT " face %s on a rigid cylinder with axis through (%g, %g, %g) along (%g, %g, %g) and radius %g, %s %g\n", z, zn.body,
                                       zn.face, (double)zn.center[0], (double)zn.center[1], (double)zn.center[2], (double)zn.axis[0], (double)zn.axis[1], (double)zn.axis[2], (double)zn.radius,
                                       ContactLaws[zn.law], (double)zn.coef));
    else if (zn.type == CONTACT_ZONE_FOUNDATION)
      PetscCall(PetscViewerASCIIPrintf(viewer, "zone %zu: body %" PetscInt_FMT " face %s on a rigid plane through (%g, %g, %g) with normal (%g, %g, %g), %s %g\n", z, zn.body, zn.face,
                                       (double)zn.point[0], (double)zn.point[1], (double)zn.point[2], (double)zn.normal[0], (double)zn.normal[1], (double)zn.normal[2], ContactLaws[zn.law],
                                       (double)zn.coef));
    else if (!d->setup)
      PetscCall(PetscViewerASCIIPrintf(viewer, "zone %zu: body %" PetscInt_FMT " face %s against body %" PetscInt_FMT " face %s (node to surface, slave %s), %s %g\n", z, zn.body, zn.face,
                                       zn.other_body, zn.other_face, ContactZoneSlaves[zn.slave], ContactLaws[zn.law], (double)zn.coef));
    else {
      const PetscBool bodyslave = d->slave[z] == zn.body ? PETSC_TRUE : PETSC_FALSE;
      PetscCall(PetscViewerASCIIPrintf(viewer,
                                       "zone %zu: body %" PetscInt_FMT " face %s against body %" PetscInt_FMT " face %s (node to surface), %s %g; slave: body %" PetscInt_FMT
                                       " face %s, search distance %g; %" PetscInt_FMT " slave nodes without a master point within it\n",
                                       z, zn.body, zn.face, zn.other_body, zn.other_face, ContactLaws[zn.law], (double)zn.coef, d->slave[z], bodyslave ? zn.face : zn.other_face, (double)d->search[z],
                                       d->unmatched[z]));
    }
  }
  if (d->cp) PetscCall(ContactProblemView(d->cp, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}
