/* A node that two contact zones share with the same row: one contact node, not two.

   A face selector takes whole boundary triangles, so two zones that split a face (z0/x<1 and z0/x>1, two physical
   surfaces side by side) share the nodes of the line between them, and two zones that select the same triangles
   share all of their nodes. Where both zones give such a node the same row (the same partner, normal and gap: the
   same obstacle plane, or the same master point; on a curved face split between two zones the copies of a
   touching slave node differ in their faces' lumped normals only, and get the normal of both), two copies of the row
   would split its force between two
   multipliers in no particular way, and each copy's pressure would divide its part of the force by its zone's part of
   the node's area: the pressure at the seam came out anything from half to twice the true one, and a zone given twice
   halved it everywhere. So the copies become one node, numbered in the first zone, whose area is that of the union of
   the zones' triangles at the node and whose friction is the integral of theirs over that area: a Coulomb F (or a
   Tresca slip bound) weighted by the area where it holds, 0 where a zone is frictionless. Rows that differ (a node at
   the edge where two obstacles meet, a slave node facing two master bodies) are different constraints and stay.

   Two zones that select the same triangle with different friction, and a Tresca zone next to a Coulomb zone, are
   errors: the surface would have two laws, or a node one that is neither. */
#include <conefeti/private/contactmodelimpl.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace {

/* rows that agree to these are the same row (the node's coordinates scale the gap) */
constexpr PetscReal kSameDirection = 1e-12;
constexpr PetscReal kSameGap       = 1e-9;
constexpr PetscReal kSameWeight    = 1e-12;

/* whether the normals differ (beyond roundoff) */
bool OtherNormal(const ContactNodeInfo &a, const ContactNodeInfo &b)
{
  for (int c = 0; c < 3; c++)
    if (std::fabs(a.n[c] - b.n[c]) > kSameDirection) return true;
  return false;
}

/* The same row: the same partner, gap and normal. Between bodies, a slave node that touches its master point takes
   its face's normal, lumped over the triangles of one zone's face: on a curved face split between two zones the
   copies at the seam then differ in the normal alone, and the row of the face they make together has their
   area-weighted normal (MergeNormal()); nodes with fixed components keep their own rule (FrictionOnRollers()). */
bool SameRow(const ContactNodeInfo &a, const ContactNodeInfo &b)
{
  if (a.other_body != b.other_body || a.nmaster != b.nmaster) return false;
  const PetscReal scale = std::max({PetscReal(1), std::fabs(a.x[0]), std::fabs(a.x[1]), std::fabs(a.x[2])});
  if (OtherNormal(a, b) && (a.other_body < 0 || a.fixed || b.fixed)) return false;
  if (std::fabs(a.gap - b.gap) > kSameGap * scale) return false;
  for (PetscInt v = 0; v < a.nmaster; v++)
    if (a.master[v] != b.master[v] || std::fabs(a.weight[v] - b.weight[v]) > kSameWeight) return false;
  return true;
}

/* the normal of the copies' faces together: their lumped normals weighted by their areas; the gap along it, and the
   tangents */
void MergeNormal(const std::vector<const ContactNodeInfo *> &copies, ContactNodeInfo &k)
{
  PetscReal n[3] = {0, 0, 0}, len = 0;
  for (const ContactNodeInfo *c : copies)
    for (int i = 0; i < 3; i++) n[i] += c->area * c->n[i];
  for (int i = 0; i < 3; i++) len += n[i] * n[i];
  len = std::sqrt(len);
  if (!(len > 0)) return;
  k.gap = 0;
  for (int i = 0; i < 3; i++) {
    k.n[i] = n[i] / len;
    k.gap += (k.chi[i] - k.x[i]) * k.n[i];
  }
  ContactTangents_Private(k.n, k.t1, k.t2);
}

/* the face of zone z on the node's body: the zone's face, or between bodies the face of whichever body is the slave */
const char *SlaveFace(const ContactZone &zone, PetscInt body) { return zone.type == CONTACT_ZONE_BODIES && body != zone.body ? zone.other_face : zone.face; }

using Triangle = std::array<PetscInt, 3>;

/* the triangles of a face at each of its nodes (indices into FEMGetTaggedTriangles()) */
using TrianglesAtNodes = std::map<PetscInt, std::vector<PetscInt>>;

struct TriangleShare {
  PetscReal  area;
  PetscInt   zone;
  ContactLaw law;
  PetscReal  coef;
};

} // namespace

/* ContactMergeSharedNodes_Private - one contact node for the copies of a node that zones give the same row
   (head of this file); the same on every rank, as the nodes are */
PetscErrorCode ContactMergeSharedNodes_Private(ContactModel cm, PetscInt *merged)
{
  ContactModelData                                            &d = *cm->data;
  std::map<std::pair<PetscInt, PetscInt>, std::vector<size_t>> copies; /* (body, node) -> its entries in d.nodes */
  std::vector<char>                                            drop(d.nodes.size(), 0);
  std::map<std::pair<PetscInt, std::string>, TrianglesAtNodes> faces; /* (body, face) -> its triangles at each node, when needed */
  MPI_Comm                                                     comm = PetscObjectComm((PetscObject)cm);

  PetscFunctionBegin;
  *merged = 0;
  for (size_t i = 0; i < d.nodes.size(); i++) PetscCallCXX(copies[{d.nodes[i].body, d.nodes[i].node}].push_back(i));
  for (auto &entry : copies) {
    std::vector<size_t> &list = entry.second;
    if (list.size() < 2) continue;
    for (size_t a = 0; a < list.size(); a++) {
      if (drop[list[a]]) continue;
      std::vector<size_t> group{list[a]};
      for (size_t b = a + 1; b < list.size(); b++)
        if (!drop[list[b]] && SameRow(d.nodes[list[a]], d.nodes[list[b]])) PetscCallCXX(group.push_back(list[b]));
      if (group.size() < 2) continue;
      const PetscInt   body = entry.first.first, node = entry.first.second;
      PetscInt         nb;
      const PetscReal *X;
      PetscCall(FEMGetBodyNodes(d.fem, body, &nb, &X));
      /* the triangles at the node, each once, with the zone (the first) and the friction of each */
      std::map<Triangle, TriangleShare> triangles;
      for (size_t g : group) {
        const ContactNodeInfo &k    = d.nodes[g];
        const char            *face = SlaveFace(d.zones[k.zone], body);
        PetscInt               ntri;
        const PetscInt        *tri;
        PetscCall(FEMGetTaggedTriangles(d.fem, body, face, &ntri, &tri));
        auto at = faces.find({body, face});
        if (at == faces.end()) {
          TrianglesAtNodes index;
          for (PetscInt t = 0; t < ntri; t++)
            for (int v = 0; v < 3; v++) PetscCallCXX(index[tri[3 * t + v]].push_back(t));
          PetscCallCXX(at = faces.emplace(std::make_pair(body, std::string(face)), std::move(index)).first);
        }
        /* the friction of this zone's triangles: F (Coulomb) or g, a stress (Tresca), as the copy has it (0 where
           friction was left out for a node on rollers, FrictionOnRollers()) */
        const PetscReal coef = k.law == CONTACT_FRICTIONLESS ? 0 : d.zones[k.zone].coef;
        for (PetscInt t : at->second[node]) {
          Triangle key{tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]};
          std::sort(key.begin(), key.end());
          auto it = triangles.find(key);
          if (it != triangles.end()) {
            const TriangleShare &s = it->second;
            PetscCheck(s.law == k.law && s.coef == coef, comm, PETSC_ERR_ARG_WRONG,
                       "contact zones %" PetscInt_FMT " and %" PetscInt_FMT " both select a boundary triangle of body %" PetscInt_FMT " at node %" PetscInt_FMT
                       " (%g, %g, %g), one %s %g, the other %s %g: a surface in contact has one law; make the zones' faces disjoint (-scene_zone%" PetscInt_FMT "_face, -scene_zone%" PetscInt_FMT
                       "_face)",
                       s.zone, k.zone, body, node, (double)k.x[0], (double)k.x[1], (double)k.x[2], ContactLaws[s.law], (double)s.coef, ContactLaws[k.law], (double)coef, s.zone, k.zone);
            continue;
          }
          const PetscReal *p = &X[3 * key[0]], *q = &X[3 * key[1]], *r = &X[3 * key[2]];
          const PetscReal  e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, f[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
          const PetscReal  c[3] = {e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]};
          PetscCallCXX(triangles.emplace(key, TriangleShare{0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / 3, k.zone, k.law, coef}));
        }
      }
      /* the node's area and the friction integrated over it */
      PetscReal area = 0, coulomb = 0, tresca = 0;
      PetscInt  zcoulomb = -1, ztresca = -1;
      for (const auto &t : triangles) {
        const TriangleShare &s = t.second;
        area += s.area;
        if (s.law == CONTACT_COULOMB) {
          coulomb += s.coef * s.area;
          zcoulomb = s.zone;
        } else if (s.law == CONTACT_TRESCA) {
          tresca += s.coef * s.area;
          ztresca = s.zone;
        }
      }
      const ContactNodeInfo &first = d.nodes[group[0]];
      PetscCheck(zcoulomb < 0 || ztresca < 0, comm, PETSC_ERR_ARG_WRONG,
                 "contact zones %" PetscInt_FMT " (Tresca) and %" PetscInt_FMT " (Coulomb) share node %" PetscInt_FMT " of body %" PetscInt_FMT
                 " (%g, %g, %g) with the same partner: its friction would be a given bound and F l_n at once; leave a row of triangles between the zones' faces, or give them one law",
                 ztresca, zcoulomb, node, body, (double)first.x[0], (double)first.x[1], (double)first.x[2]);
      const ContactLaw law = zcoulomb >= 0 ? CONTACT_COULOMB : ztresca >= 0 ? CONTACT_TRESCA : CONTACT_FRICTIONLESS;
      /* the copy that keeps the node: the first with the merged law (its tangents were made for it), else the first */
      size_t keep = group[0];
      for (size_t g : group)
        if (d.nodes[g].law == law) {
          keep = g;
          break;
        }
      ContactNodeInfo k = d.nodes[keep];
      {
        std::vector<const ContactNodeInfo *> rows; /* the group's copies */
        bool                                 other = false;
        for (size_t g : group) {
          PetscCallCXX(rows.push_back(&d.nodes[g]));
          other = other || OtherNormal(d.nodes[g], d.nodes[group[0]]);
        }
        if (other) MergeNormal(rows, k);
      }
      k.zone            = first.zone;
      k.law             = law;
      k.coef            = law == CONTACT_COULOMB ? coulomb / area : law == CONTACT_TRESCA ? tresca : 0;
      k.area            = area;
      d.nodes[group[0]] = k; /* in the first zone's place */
      for (size_t g = 1; g < group.size(); g++) drop[group[g]] = 1;
      *merged += (PetscInt)group.size() - 1;
    }
  }
  if (*merged) {
    std::vector<ContactNodeInfo> kept;
    PetscCallCXX(kept.reserve(d.nodes.size() - *merged));
    for (size_t i = 0; i < d.nodes.size(); i++)
      if (!drop[i]) PetscCallCXX(kept.push_back(d.nodes[i]));
    PetscCallCXX(d.nodes.swap(kept));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
