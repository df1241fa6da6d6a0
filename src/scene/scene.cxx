/* ContactScene: a FEM model with contact zones read from -scene_* options (docs/scenes.md).

   Parsing is strict: every value is checked before PETSc converts it, so a bad value gives an error
   that names the option and the value; a -scene_* option that no body or zone uses (a typo, or a
   body/zone index after a gap) is an error, not a warning at the end of the run. */
#include <algorithm>
#include "sceneimpl.h"
#include <conefeti/private/format.h>
#include <conefeti/private/errortext.h>

#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>

PetscClassId      CONTACTSCENE_CLASSID;
PetscLogEvent     CONTACTSCENE_SetUp, CONTACTSCENE_Solve, CONTACTSCENE_Summary, CONTACTSCENE_Output;
const char *const SceneFaceNames[6] = {"x0", "x1", "y0", "y1", "z0", "z1"};

namespace {

const PetscInt MaxList = 16; /* entries of a list option (e.g. -scene_body0_fix) */

/* What the parser needs to read and check options: the prefix and the communicator for errors */
struct Reader {
  CONEFETI_OPTIONS_ITEMS PetscOptionsObject;
  const char            *prefix;
  MPI_Comm               comm;
  PetscBool              help;

  /* "-<prefix>name" for messages, from "-name" */
  std::string Full(const std::string &name) const { return "-" + std::string(prefix ? prefix : "") + name.substr(1); }

  PetscErrorCode Raw(const std::string &name, std::string &value, PetscBool *set) const
  {
    char buf[4096];

    PetscFunctionBegin;
    buf[0] = 0;
    PetscCall(PetscOptionsGetString(NULL, prefix, name.c_str(), buf, sizeof(buf), set));
    value = buf;
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode Has(const std::string &name, PetscBool *set) const
  {
    PetscFunctionBegin;
    PetscCall(PetscOptionsHasName(NULL, prefix, name.c_str(), set));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  static void Split(const std::string &raw, std::vector<std::string> &tokens)
  {
    std::string cur;
    tokens.clear();
    for (char c : raw) {
      if (c == ',') {
        tokens.push_back(cur);
        cur.clear();
      } else if (c != ' ' && c != '\t') cur += c;
    }
    tokens.push_back(cur);
  }

  /* check that the option's value is nmin..nmax comma-separated finite numbers (integers when integer) */
  PetscErrorCode CheckNumbers(const std::string &name, PetscInt nmin, PetscInt nmax, PetscBool integer, const char *what) const
  {
    std::string              raw;
    std::vector<std::string> tokens;
    PetscBool                set;

    PetscFunctionBegin;
    PetscCall(Raw(name, raw, &set));
    if (!set) PetscFunctionReturn(PETSC_SUCCESS);
    PetscCheck(!raw.empty(), comm, PETSC_ERR_ARG_WRONG, "%s needs a value: %s", Full(name).c_str(), what);
    Split(raw, tokens);
    const PetscInt n = (PetscInt)tokens.size();
    PetscCheck(n >= nmin && n <= nmax, comm, PETSC_ERR_ARG_WRONG, "%s %s: %" PetscInt_FMT " value%s given, expected %s", Full(name).c_str(), raw.c_str(), n, n == 1 ? "" : "s", what);
    for (const std::string &t : tokens) {
      char *end = nullptr;
      errno     = 0;
      if (integer) {
        const long long v = t.empty() ? 0 : std::strtoll(t.c_str(), &end, 10);
        PetscCheck(!t.empty() && *end == 0 && errno == 0 && v >= PETSC_MIN_INT && v <= PETSC_MAX_INT, comm, PETSC_ERR_ARG_WRONG, "%s %s: '%s' is not an integer (expected %s)", Full(name).c_str(),
                   raw.c_str(), t.c_str(), what);
      } else {
        const double v = t.empty() ? 0 : std::strtod(t.c_str(), &end);
        PetscCheck(!t.empty() && *end == 0 && std::isfinite(v), comm, PETSC_ERR_ARG_WRONG, "%s %s: '%s' is not a finite number (expected %s)", Full(name).c_str(), raw.c_str(), t.c_str(), what);
      }
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode Reals(const std::string &name, const char *help, const char *what, PetscInt nmin, PetscInt nmax, PetscReal v[], PetscInt *n, PetscBool *set) const
  {
    PetscInt cnt = nmax;

    PetscFunctionBegin;
    PetscCall(CheckNumbers(name, nmin, nmax, PETSC_FALSE, what));
    PetscCall(PetscOptionsRealArray(name.c_str(), help, "ContactSceneSetFromOptions", v, &cnt, set));
    if (n) *n = cnt;
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode Real(const std::string &name, const char *help, const char *what, PetscReal *v, PetscBool *set) const
  {
    PetscFunctionBegin;
    PetscCall(CheckNumbers(name, 1, 1, PETSC_FALSE, what));
    PetscCall(PetscOptionsReal(name.c_str(), help, "ContactSceneSetFromOptions", *v, v, set));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode Ints(const std::string &name, const char *help, const char *what, PetscInt nmin, PetscInt nmax, PetscInt v[], PetscInt *n, PetscBool *set) const
  {
    PetscInt cnt = nmax;

    PetscFunctionBegin;
    PetscCall(CheckNumbers(name, nmin, nmax, PETSC_TRUE, what));
    PetscCall(PetscOptionsIntArray(name.c_str(), help, "ContactSceneSetFromOptions", v, &cnt, set));
    if (n) *n = cnt;
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode Int(const std::string &name, const char *help, const char *what, PetscInt *v, PetscBool *set) const
  {
    PetscFunctionBegin;
    PetscCall(CheckNumbers(name, 1, 1, PETSC_TRUE, what));
    PetscCall(PetscOptionsInt(name.c_str(), help, "ContactSceneSetFromOptions", *v, v, set));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  /* an enum given by one of the names of list (a PETSc enum list: names, then the type name, prefix, NULL) */
  PetscErrorCode Enum(const std::string &name, const char *help, const char *const *list, PetscEnum *v, PetscBool *set) const
  {
    std::string raw, choices;
    PetscBool   has, found = PETSC_FALSE;
    PetscInt    count = 0;

    PetscFunctionBegin;
    while (list[count]) count++;
    count -= 2; /* the type name and the prefix follow the names */
    PetscCall(Raw(name, raw, &has));
    if (has) {
      for (PetscInt i = 0; i < count; i++) {
        PetscBool eq;
        PetscCall(PetscStrcasecmp(raw.c_str(), list[i], &eq));
        if (eq) found = PETSC_TRUE;
        choices += (i ? (i == count - 1 ? " or " : ", ") : "") + std::string(list[i]);
      }
      PetscCheck(found, comm, PETSC_ERR_ARG_WRONG, "%s '%s': unknown value (use %s)", Full(name).c_str(), raw.c_str(), choices.c_str());
    }
    PetscCall(PetscOptionsEnum(name.c_str(), help, "ContactSceneSetFromOptions", list, *v, v, set));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode String(const std::string &name, const char *help, const char *what, std::string &v, PetscBool *set) const
  {
    char buf[256];

    PetscFunctionBegin;
    PetscCall(PetscStrncpy(buf, v.c_str(), sizeof(buf)));
    PetscCall(PetscOptionsString(name.c_str(), help, "ContactSceneSetFromOptions", buf, buf, sizeof(buf), set));
    if (*set) {
      PetscCheck(buf[0], comm, PETSC_ERR_ARG_WRONG, "%s needs a value: %s", Full(name).c_str(), what);
      v = buf;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode Strings(const std::string &name, const char *help, const char *what, std::vector<std::string> &v, PetscBool *set) const
  {
    std::string              raw;
    std::vector<std::string> tokens;
    PetscBool                has;
    char                    *arr[MaxList];
    PetscInt                 n = MaxList;

    PetscFunctionBegin;
    PetscCall(Raw(name, raw, &has));
    if (has) {
      PetscCheck(!raw.empty(), comm, PETSC_ERR_ARG_WRONG, "%s needs a value: %s", Full(name).c_str(), what);
      Split(raw, tokens);
      PetscCheck((PetscInt)tokens.size() <= MaxList, comm, PETSC_ERR_ARG_WRONG, "%s: at most %" PetscInt_FMT " entries, got %d", Full(name).c_str(), MaxList, (int)tokens.size());
      for (const std::string &t : tokens) PetscCheck(!t.empty(), comm, PETSC_ERR_ARG_WRONG, "%s %s: empty entry (expected %s)", Full(name).c_str(), raw.c_str(), what);
    }
    PetscCall(PetscOptionsStringArray(name.c_str(), help, "ContactSceneSetFromOptions", arr, &n, set));
    v.clear();
    if (*set)
      for (PetscInt i = 0; i < n; i++) {
        v.push_back(arr[i]);
        PetscCall(PetscFree(arr[i]));
      }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

const char *const SelectorUsage = "use FACE or FACE/COND[/COND...] with FACE one of x0 x1 y0 y1 z0 z1 (or, on a body from -scene_body<b>_mesh, a physical surface of the mesh) and COND like x>1, "
                                  "y<=0.5 (a condition on the centroids of the face's triangles)";

/* The boundary tag of a selector with conditions is its text. A contact zone keeps its faces' tags in
   ContactZone's fixed-size names, so a longer text (conditions with many digits) is tagged by its start and a
   hash of the whole (FNV-1a), which is as unique as the text and the same on every rank */
std::string ConditionTag(const std::string &text)
{
  constexpr size_t kMax = sizeof(ContactZone::face) - 1;
  if (text.size() <= kMax) return text;
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", (unsigned long long)h);
  return text.substr(0, kMax - 1 - (sizeof(hex) - 1)) + "#" + hex; /* start, '#', 16 hex digits */
}

/* FACE[/AXIS OP VALUE]..., OP one of > >= < <= */
PetscErrorCode ParseSelector(MPI_Comm comm, const std::string &option, const std::string &given, SceneSelector &sel)
{
  std::string              text;
  std::vector<std::string> parts;
  std::string              cur;
  const char              *usage = SelectorUsage;

  PetscFunctionBegin;
  for (char c : given)
    if (c != ' ' && c != '\t') text += c;
  for (char c : text) {
    if (c == '/') {
      parts.push_back(cur);
      cur.clear();
    } else cur += c;
  }
  parts.push_back(cur);
  sel        = SceneSelector{};
  sel.text   = text;
  sel.option = option;
  for (PetscInt f = 0; f < 6; f++)
    if (parts[0] == SceneFaceNames[f]) sel.face = f;
  /* any other FACE is a physical surface of a mesh body, checked against the mesh file at setup (and against the
     body's kind by CheckBoxSelectors()) */
  PetscCheck(sel.face >= 0 || !parts[0].empty(), comm, PETSC_ERR_ARG_WRONG, "%s '%s': no face before the first '/' (%s)", option.c_str(), given.c_str(), usage);
  if (sel.face < 0) sel.name = parts[0];
  for (size_t i = 1; i < parts.size(); i++) {
    const std::string &p = parts[i];
    SceneCondition     c{};
    size_t             k = 1;
    PetscCheck(p.size() >= 3 && (p[0] == 'x' || p[0] == 'y' || p[0] == 'z') && (p[1] == '<' || p[1] == '>'), comm, PETSC_ERR_ARG_WRONG, "%s '%s': condition '%s' is not AXIS OP VALUE (%s)",
               option.c_str(), given.c_str(), p.c_str(), usage);
    c.axis    = p[0] - 'x';
    c.greater = p[1] == '>' ? PETSC_TRUE : PETSC_FALSE;
    k         = 2;
    if (p[2] == '=') {
      c.equal = PETSC_TRUE;
      k       = 3;
    }
    const std::string num = p.substr(k);
    char             *end = nullptr;
    const double      v   = num.empty() ? 0 : std::strtod(num.c_str(), &end);
    PetscCheck(!num.empty() && *end == 0 && std::isfinite(v), comm, PETSC_ERR_ARG_WRONG, "%s '%s': '%s' in condition '%s' is not a finite number", option.c_str(), given.c_str(), num.c_str(),
               p.c_str());
    c.value = v;
    sel.conditions.push_back(c);
  }
  sel.tag = sel.conditions.empty() ? (sel.face >= 0 ? std::string(SceneFaceNames[sel.face]) : sel.name) : ConditionTag(text);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SelectorPredicate(const PetscReal centroid[3], const PetscReal normal[3], PetscBool *tagged, void *ctx)
{
  const SceneSelector *sel  = (const SceneSelector *)ctx;
  PetscInt             axis = 0;

  for (PetscInt d = 1; d < 3; d++)
    if (std::fabs(normal[d]) > std::fabs(normal[axis])) axis = d;
  /* a physical surface's triangles are chosen by FEMTagFacesWithin(): only the conditions are left */
  *tagged = sel->face < 0 || (2 * axis + (normal[axis] > 0 ? 1 : 0)) == sel->face ? PETSC_TRUE : PETSC_FALSE;
  for (const SceneCondition &c : sel->conditions) {
    const PetscReal x  = centroid[c.axis];
    const PetscBool ok = c.greater ? (c.equal ? (x >= c.value ? PETSC_TRUE : PETSC_FALSE) : (x > c.value ? PETSC_TRUE : PETSC_FALSE))
                                   : (c.equal ? (x <= c.value ? PETSC_TRUE : PETSC_FALSE) : (x < c.value ? PETSC_TRUE : PETSC_FALSE));
    if (!ok) *tagged = PETSC_FALSE;
  }
  return PETSC_SUCCESS;
}

PetscErrorCode ConstantForce(const PetscReal *, PetscReal value[3], void *ctx)
{
  const PetscReal *f = (const PetscReal *)ctx;
  for (PetscInt d = 0; d < 3; d++) value[d] = f[d];
  return PETSC_SUCCESS;
}

PetscErrorCode AnySet(const Reader &r, const std::string &stem, std::initializer_list<const char *> keys, PetscBool *any)
{
  PetscFunctionBegin;
  *any = PETSC_FALSE;
  for (const char *k : keys) {
    PetscBool set;
    PetscCall(r.Has(stem + k, &set));
    if (set) *any = PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReadBody(const Reader &r, PetscInt b, PetscBool exists, SceneBody &body)
{
  const std::string s    = ConeFETIFormat("-scene_body%d_", (int)b);
  const MPI_Comm    comm = r.comm;
  PetscBool         set, setlo, setup, setcells, setE, setnu, setdec, setparts;
  PetscInt          n, parts[3] = {1, 1, 1};
  PetscReal         femE = 2.12e11, femnu = 0.277;

  PetscBool setmesh, setscale, settranslate, setvolume;

  PetscFunctionBegin;
  PetscCall(r.Reals(s + "lower", "Lower corner of the box (x,y,z)", "3 numbers x,y,z", 3, 3, body.lower.data(), NULL, &setlo));
  PetscCall(r.Reals(s + "upper", "Upper corner of the box (x,y,z)", "3 numbers x,y,z", 3, 3, body.upper.data(), NULL, &setup));
  PetscCall(r.Ints(s + "cells", "Hexahedra along x,y,z (each cut into 6 tetrahedra), multiplied by -scene_refine", "3 positive integers nx,ny,nz", 3, 3, body.cells.data(), NULL, &setcells));
  /* or a mesh file of tetrahedra (instead of the box options) */
  PetscCall(r.String(s + "mesh", "Mesh file of tetrahedra (Gmsh .msh 2.2/4.x, or any DMPlexCreateFromFile() format) instead of a box", "a mesh file name", body.mesh, &setmesh));
  PetscCall(r.Real(s + "scale", "Mesh: multiply the file's coordinates by this factor (e.g. 1e-3 for a mesh in mm)", "a scale factor > 0", &body.scale, &setscale));
  PetscCall(r.Reals(s + "translate", "Mesh: then add this vector to the coordinates", "3 numbers x,y,z", 3, 3, body.translate.data(), NULL, &settranslate));
  PetscCall(r.String(s + "volume", "Mesh: only the cells of this physical volume (a name or number of the file)", "a physical volume", body.volume, &setvolume));
  if (exists && setmesh) {
    PetscCheck(!setlo && !setup && !setcells, comm, PETSC_ERR_ARG_WRONG, "body %d has both %s and %s: a body is either a mesh file or a box (_lower, _upper, _cells)", (int)b,
               r.Full(s + "mesh").c_str(),
               r.Full(s + (setlo   ? "lower"
                           : setup ? "upper"
                                   : "cells"))
                   .c_str());
    PetscCheck(body.scale > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: the scale must be positive (a mirror image would turn every tetrahedron inside out)", r.Full(s + "scale").c_str(),
               (double)body.scale);
  } else if (exists) {
    PetscCheck(!setscale && !settranslate && !setvolume, comm, PETSC_ERR_ARG_WRONG, "%s applies to a body from a mesh file: body %d is a box (give %s, or remove it)",
               r.Full(s + (setscale       ? "scale"
                           : settranslate ? "translate"
                                          : "volume"))
                   .c_str(),
               (int)b, r.Full(s + "mesh").c_str());
  }
  if (exists && !setmesh) {
    PetscCheck(setlo && setup && setcells, comm, PETSC_ERR_ARG_WRONG, "body %d needs %s, %s and %s", (int)b, r.Full(s + "lower").c_str(), r.Full(s + "upper").c_str(), r.Full(s + "cells").c_str());
    for (PetscInt d = 0; d < 3; d++) {
      PetscCheck(body.upper[d] > body.lower[d], comm, PETSC_ERR_ARG_OUTOFRANGE, "%s and %s: upper %g must exceed lower %g along %c", r.Full(s + "lower").c_str(), r.Full(s + "upper").c_str(),
                 (double)body.upper[d], (double)body.lower[d], (char)('x' + d));
      PetscCheck(body.cells[d] >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: %" PetscInt_FMT " cells along %c, need at least 1", r.Full(s + "cells").c_str(), body.cells[d], (char)('x' + d));
    }
  }
  /* material: the body's own, else -fem_E / -fem_nu, else steel */
  PetscCall(PetscOptionsGetReal(NULL, r.prefix, "-fem_E", &femE, NULL));
  PetscCall(PetscOptionsGetReal(NULL, r.prefix, "-fem_nu", &femnu, NULL));
  body.E  = femE;
  body.nu = femnu;
  PetscCall(r.Real(s + "E", "Young's modulus (default -fem_E, else steel 2.12e11)", "Young's modulus E > 0", &body.E, &setE));
  PetscCall(r.Real(s + "nu", "Poisson's ratio (default -fem_nu, else 0.277)", "Poisson's ratio in (-1, 0.5)", &body.nu, &setnu));
  if (exists) {
    PetscCheck(body.E > 0 && !PetscIsInfOrNanReal(body.E), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: Young's modulus must be positive and finite", setE ? r.Full(s + "E").c_str() : "-fem_E",
               (double)body.E);
    PetscCheck(body.nu > -1 && body.nu < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: Poisson's ratio must lie in (-1, 0.5)", setnu ? r.Full(s + "nu").c_str() : "-fem_nu", (double)body.nu);
  }
  /* decomposition */
  PetscCall(r.Enum(s + "decomposition", "How the body is cut into subdomains (default: from the count of -scene_body<b>_subdomains, else -fem_decomposition)", FEMDecompositionTypes,
                   (PetscEnum *)&body.decomposition, &setdec));
  PetscCall(r.Ints(s + "subdomains", "Subdomains: px,py,pz (structured) or n (metis)", "px,py,pz (structured) or one count n (metis)", 1, 3, parts, &n, &setparts));
  if (exists && setmesh && (setdec || setparts)) {
    PetscCheck(!(setdec && body.decomposition == FEM_DECOMPOSITION_STRUCTURED) && !(setparts && n != 1), comm, PETSC_ERR_ARG_WRONG,
               "%s: a body from a mesh file is decomposed by METIS only: give one subdomain count, %s n", r.Full(s + (setparts && n != 1 ? "subdomains" : "decomposition")).c_str(),
               r.Full(s + "subdomains").c_str());
    body.decomposition = FEM_DECOMPOSITION_METIS;
  }
  if (exists && (setdec || setparts)) {
    if (!setdec) body.decomposition = n == 1 ? FEM_DECOMPOSITION_METIS : FEM_DECOMPOSITION_STRUCTURED;
    if (body.decomposition == FEM_DECOMPOSITION_STRUCTURED) {
      if (!setparts) n = 3;
      PetscCheck(n == 3, comm, PETSC_ERR_ARG_WRONG, "%s: the structured decomposition needs px,py,pz, got %" PetscInt_FMT " value%s", r.Full(s + "subdomains").c_str(), n, n == 1 ? "" : "s");
    } else {
      PetscCheck(setparts && n == 1, comm, PETSC_ERR_ARG_WRONG, "%s metis needs one subdomain count: %s n", r.Full(s + "decomposition").c_str(), r.Full(s + "subdomains").c_str());
      parts[1] = parts[2] = 1;
    }
    for (PetscInt d = 0; d < 3; d++) PetscCheck(parts[d] >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: subdomain count %" PetscInt_FMT " must be positive", r.Full(s + "subdomains").c_str(), parts[d]);
    for (PetscInt d = 0; d < 3; d++) body.parts[d] = parts[d];
    body.decompositionset = PETSC_TRUE;
  }
  /* supports */
  body.supports.clear();
  {
    const char *keys[4]  = {"fix", "fix_x", "fix_y", "fix_z"};
    const char *helps[4] = {"Faces (or parts of faces) with zero displacement: FACE[/COND...],...", "Faces with zero x displacement (e.g. a symmetry plane x = const)",
                            "Faces with zero y displacement", "Faces with zero z displacement"};
    for (PetscInt k = 0; k < 4; k++) {
      std::vector<std::string> list;
      PetscCall(r.Strings(s + keys[k], helps[k], "face selectors FACE[/COND...]", list, &set));
      if (!exists) continue;
      for (const std::string &t : list) {
        SceneSupport sp;
        PetscCall(ParseSelector(comm, r.Full(s + keys[k]), t, sp.selector));
        sp.mask = k == 0 ? 7u : (1u << (k - 1));
        sp.kind = keys[k];
        body.supports.push_back(sp);
      }
    }
  }
  /* displaced faces (grips, punches): face k moved by a given vector, all components (_value) or some (_x, _y, _z) */
  for (PetscInt k = 0; k < MaxList; k++) {
    const std::string        stem = ConeFETIFormat("%sdisplace%d_", s.c_str(), (int)k), sf = stem + "face", sv = stem + "value";
    const std::string        sc[3] = {stem + "x", stem + "y", stem + "z"};
    PetscBool                has, any, setv, setc[3];
    std::vector<std::string> list;
    std::array<PetscReal, 3> value{};
    unsigned                 mask = 0;
    PetscCall(r.Has(sf, &has));
    PetscCall(AnySet(r, stem, {"face", "value", "x", "y", "z"}, &any));
    if (!any && !(r.help && k == 0)) break;
    PetscCall(r.Strings(sf, "Faces (or parts) moved by displacement <k>: FACE[/COND...],... (a grip or a punch)", "face selectors FACE[/COND...]", list, &set));
    PetscCall(r.Reals(sv, "Displacement <k> ux,uy,uz of those faces (every component prescribed)", "3 numbers ux,uy,uz", 3, 3, value.data(), NULL, &setv));
    for (PetscInt c = 0; c < 3; c++) {
      const char *help[3] = {"Displacement <k>: only the x component prescribed (y, z free unless given)", "Displacement <k>: only the y component prescribed",
                             "Displacement <k>: only the z component prescribed"};
      PetscCall(r.Real(sc[c], help[c], "a displacement component", &value[c], &setc[c]));
      if (setc[c]) mask |= 1u << c;
    }
    if (!exists || !any) continue;
    PetscCheck(has, comm, PETSC_ERR_ARG_WRONG, "displacement %d of body %d needs %s (the faces it moves)", (int)k, (int)b, r.Full(sf).c_str());
    PetscCheck(setv || mask, comm, PETSC_ERR_ARG_WRONG, "displacement %d of body %d needs %s ux,uy,uz, or the components it prescribes: %s, %s, %s", (int)k, (int)b, r.Full(sv).c_str(),
               r.Full(sc[0]).c_str(), r.Full(sc[1]).c_str(), r.Full(sc[2]).c_str());
    PetscCheck(!(setv && mask), comm, PETSC_ERR_ARG_WRONG, "displacement %d of body %d: %s prescribes every component, so %s cannot be given with it (use %s, %s, %s alone to leave components free)",
               (int)k, (int)b, r.Full(sv).c_str(),
               r.Full(sc[setc[0]   ? 0
                         : setc[1] ? 1
                                   : 2])
                   .c_str(),
               r.Full(sc[0]).c_str(), r.Full(sc[1]).c_str(), r.Full(sc[2]).c_str());
    if (setv) mask = 7u;
    for (const std::string &t : list) {
      SceneSupport sp;
      PetscCall(ParseSelector(comm, r.Full(sf), t, sp.selector));
      sp.mask     = mask;
      sp.value    = value;
      sp.displace = k;
      sp.kind     = ConeFETIFormat("displace%d", (int)k);
      body.supports.push_back(sp);
    }
  }
  /* tractions: per whole face, then on parts of faces */
  body.tractions.clear();
  for (PetscInt f = 0; f < 6; f++) {
    SceneTraction     t;
    const std::string name = s + "traction_" + SceneFaceNames[f];
    PetscCall(r.Reals(name, "Constant traction (force per area) tx,ty,tz on the face", "3 numbers tx,ty,tz", 3, 3, t.value.data(), NULL, &set));
    if (!exists || !set) continue;
    PetscCall(ParseSelector(comm, r.Full(name), SceneFaceNames[f], t.selector));
    body.tractions.push_back(t);
  }
  for (PetscInt k = 0; k < MaxList; k++) {
    const std::string sf = ConeFETIFormat("%straction%d_face", s.c_str(), (int)k), sv = ConeFETIFormat("%straction%d_value", s.c_str(), (int)k);
    PetscBool         has, hasv, setv;
    SceneTraction     t;
    std::string       text;
    PetscCall(r.Has(sf, &has));
    PetscCall(r.Has(sv, &hasv));
    if (!has && !hasv && !(r.help && k == 0)) break;
    PetscCall(r.String(sf, "Part of a face carrying traction <k>: FACE/COND... (e.g. z1/x<1)", "a face selector", text, &set));
    PetscCall(r.Reals(sv, "Traction <k> (force per area) tx,ty,tz", "3 numbers tx,ty,tz", 3, 3, t.value.data(), NULL, &setv));
    if (!exists || (!has && !hasv)) continue;
    PetscCheck(has && hasv, comm, PETSC_ERR_ARG_WRONG, "traction %d of body %d needs both %s and %s", (int)k, (int)b, r.Full(sf).c_str(), r.Full(sv).c_str());
    PetscCall(ParseSelector(comm, r.Full(sf), text, t.selector));
    body.tractions.push_back(t);
  }
  PetscCall(r.Reals(s + "force", "Constant volume force density fx,fy,fz (force per volume, e.g. density times gravity); none when not given", "3 numbers fx,fy,fz", 3, 3, body.force.data(), NULL,
                    &body.hasforce));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReadZone(const Reader &r, PetscInt z, PetscBool exists, PetscInt nbodies, SceneZoneSpec &spec)
{
  const std::string s    = ConeFETIFormat("-scene_zone%d_", (int)z);
  const MPI_Comm    comm = r.comm;
  ContactZone      &zone = spec.zone;
  PetscBool         set, setface, setpoint, setnormal, setother, setotherface, setlaw, setF, setg, setshape, setcenter, setaxis, setradius, setslave, setsearch;
  std::string       face, other;
  PetscReal         F = 0, g = 0;

  PetscFunctionBegin;
  zone           = ContactZone{};
  zone.type      = CONTACT_ZONE_FOUNDATION;
  zone.normal[2] = 1;
  zone.law       = CONTACT_FRICTIONLESS;
  PetscCall(r.Enum(s + "type", "Where the zone touches: foundation (a rigid obstacle) or bodies (another body, node to surface)", ContactZoneTypes, (PetscEnum *)&zone.type, &set));
  PetscCall(r.Int(s + "body", "The body whose face may touch", "a body index", &zone.body, &set));
  PetscCall(r.String(s + "face", "The face (or part) that may touch: FACE[/COND...], e.g. z0/x>1", "a face selector", face, &setface));
  PetscCall(r.Reals(s + "point", "Foundation: a point of the rigid plane", "3 numbers x,y,z", 3, 3, zone.point, NULL, &setpoint));
  PetscCall(r.Reals(s + "normal", "Foundation: the plane's normal, pointing toward the body (the gap of x is (x - point).normal)", "3 numbers nx,ny,nz", 3, 3, zone.normal, NULL, &setnormal));
  PetscCall(r.Enum(s + "shape", "Foundation: the rigid obstacle, plane (_point, _normal), sphere (_center, _radius) or cylinder (_center, _axis, _radius); the body lies outside it",
                   ContactObstacleShapes, (PetscEnum *)&zone.shape, &setshape));
  PetscCall(r.Reals(s + "center", "Foundation, sphere: its center; cylinder: a point of its axis", "3 numbers x,y,z", 3, 3, zone.center, NULL, &setcenter));
  PetscCall(r.Reals(s + "axis", "Foundation, cylinder: the axis direction", "3 numbers ax,ay,az", 3, 3, zone.axis, NULL, &setaxis));
  PetscCall(r.Real(s + "radius", "Foundation, sphere or cylinder: the radius > 0", "a radius > 0", &zone.radius, &setradius));
  PetscCall(r.Int(s + "other_body", "Bodies: the other body", "a body index", &zone.other_body, &setother));
  PetscCall(r.String(s + "other_face", "Bodies: the other body's face (any mesh: node to surface)", "a face selector", other, &setotherface));
  PetscCall(r.Enum(s + "slave",
                   "Bodies: the slave face, whose nodes are paired with the closest point of the other (master) face: finer (smaller mean edge; a tie: _face), body (_face) or other (_other_face)",
                   ContactZoneSlaves, (PetscEnum *)&zone.slave, &setslave));
  PetscCall(r.Real(s + "search_distance", "Bodies: slave nodes without a master point within this distance are not contact nodes (default: the master face's longest triangle edge)", "a distance > 0",
                   &zone.search_distance, &setsearch));
  PetscCall(r.Enum(s + "law", "Contact law: frictionless, tresca (given slip bound) or coulomb (friction coefficient)", ContactLaws, (PetscEnum *)&zone.law, &setlaw));
  PetscCall(r.Real(s + "friction", "Coulomb: the friction coefficient F >= 0", "a friction coefficient F >= 0", &F, &setF));
  PetscCall(r.Real(s + "slip_bound", "Tresca: the slip bound, a tangential stress (force per area) >= 0", "a slip bound (stress) >= 0", &g, &setg));
  if (!exists) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(setface, comm, PETSC_ERR_ARG_WRONG, "contact zone %d needs %s (e.g. z0, or z0/x>1 for part of a face)", (int)z, r.Full(s + "face").c_str());
  PetscCheck(setlaw, comm, PETSC_ERR_ARG_WRONG, "contact zone %d needs %s frictionless, tresca or coulomb", (int)z, r.Full(s + "law").c_str());
  PetscCheck(zone.body >= 0 && zone.body < nbodies, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %" PetscInt_FMT ": no such body (the scene has %" PetscInt_FMT " bod%s, numbered from 0)",
             r.Full(s + "body").c_str(), zone.body, nbodies, nbodies == 1 ? "y" : "ies");
  PetscCall(ParseSelector(comm, r.Full(s + "face"), face, spec.face));
  if (zone.type == CONTACT_ZONE_FOUNDATION) {
    PetscCheck(!setother && !setotherface, comm, PETSC_ERR_ARG_WRONG, "contact zone %d is a foundation zone: %s and %s belong to -scene_zone%d_type bodies", (int)z, r.Full(s + "other_body").c_str(),
               r.Full(s + "other_face").c_str(), (int)z);
    PetscCheck(!setslave && !setsearch, comm, PETSC_ERR_ARG_WRONG, "contact zone %d is a foundation zone: %s belongs to -scene_zone%d_type bodies", (int)z,
               r.Full(s + (setslave ? "slave" : "search_distance")).c_str(), (int)z);
    const char *shape = ContactObstacleShapes[zone.shape];
    if (zone.shape == CONTACT_OBSTACLE_PLANE) {
      PetscCheck(!setcenter && !setaxis && !setradius, comm, PETSC_ERR_ARG_WRONG, "foundation zone %d is a plane: %s belongs to %s sphere or cylinder", (int)z,
                 r.Full(s + (setcenter ? "center"
                             : setaxis ? "axis"
                                       : "radius"))
                     .c_str(),
                 r.Full(s + "shape").c_str());
      PetscCheck(setnormal, comm, PETSC_ERR_ARG_WRONG, "foundation zone %d needs %s nx,ny,nz (the plane's normal, pointing toward the body)", (int)z, r.Full(s + "normal").c_str());
      const PetscReal len = std::max({std::fabs(zone.normal[0]), std::fabs(zone.normal[1]), std::fabs(zone.normal[2])}); /* only nonzero matters: no squares to overflow */
      PetscCheck(len > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the normal must be nonzero", r.Full(s + "normal").c_str());
    } else {
      PetscCheck(!setpoint && !setnormal, comm, PETSC_ERR_ARG_WRONG, "foundation zone %d is a %s: %s belongs to %s plane", (int)z, shape, r.Full(s + (setpoint ? "point" : "normal")).c_str(),
                 r.Full(s + "shape").c_str());
      PetscCheck(setcenter, comm, PETSC_ERR_ARG_WRONG, "foundation zone %d is a %s: it needs %s x,y,z (%s)", (int)z, shape, r.Full(s + "center").c_str(),
                 zone.shape == CONTACT_OBSTACLE_SPHERE ? "the sphere's center" : "a point of the cylinder's axis");
      PetscCheck(setradius, comm, PETSC_ERR_ARG_WRONG, "foundation zone %d is a %s: it needs %s R (> 0)", (int)z, shape, r.Full(s + "radius").c_str());
      PetscCheck(zone.radius > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: the %s's radius must be > 0", r.Full(s + "radius").c_str(), (double)zone.radius, shape);
      if (zone.shape == CONTACT_OBSTACLE_SPHERE) PetscCheck(!setaxis, comm, PETSC_ERR_ARG_WRONG, "foundation zone %d is a sphere: %s belongs to cylinders", (int)z, r.Full(s + "axis").c_str());
      else {
        PetscCheck(setaxis, comm, PETSC_ERR_ARG_WRONG, "foundation zone %d is a cylinder: it needs %s ax,ay,az (the axis direction)", (int)z, r.Full(s + "axis").c_str());
        const PetscReal len = std::max({std::fabs(zone.axis[0]), std::fabs(zone.axis[1]), std::fabs(zone.axis[2])});
        PetscCheck(len > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the cylinder's axis must be nonzero", r.Full(s + "axis").c_str());
      }
    }
  } else {
    PetscCheck(!setshape && !setcenter && !setaxis && !setradius, comm, PETSC_ERR_ARG_WRONG, "contact zone %d is between bodies: %s belongs to foundation zones", (int)z,
               r.Full(s + (setshape    ? "shape"
                           : setcenter ? "center"
                           : setaxis   ? "axis"
                                       : "radius"))
                   .c_str());
    PetscCheck(!setpoint && !setnormal, comm, PETSC_ERR_ARG_WRONG, "contact zone %d is between bodies: %s and %s belong to foundation zones (the normal is the first face's)", (int)z,
               r.Full(s + "point").c_str(), r.Full(s + "normal").c_str());
    PetscCheck(setother && setotherface, comm, PETSC_ERR_ARG_WRONG, "contact zone %d between bodies needs %s and %s", (int)z, r.Full(s + "other_body").c_str(), r.Full(s + "other_face").c_str());
    PetscCheck(zone.other_body >= 0 && zone.other_body < nbodies && zone.other_body != zone.body, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s %" PetscInt_FMT ": must be a body of the scene (0..%" PetscInt_FMT ") other than %s %" PetscInt_FMT, r.Full(s + "other_body").c_str(), zone.other_body, nbodies - 1,
               r.Full(s + "body").c_str(), zone.body);
    PetscCall(ParseSelector(comm, r.Full(s + "other_face"), other, spec.other));
    PetscCheck(!setsearch || (zone.search_distance > 0 && zone.search_distance < PETSC_MAX_REAL), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: the search distance must be finite and > 0",
               r.Full(s + "search_distance").c_str(), (double)zone.search_distance);
  }
  switch (zone.law) {
  case CONTACT_FRICTIONLESS:
    PetscCheck(!setF && !setg, comm, PETSC_ERR_ARG_WRONG, "contact zone %d is frictionless: remove %s", (int)z, setF ? r.Full(s + "friction").c_str() : r.Full(s + "slip_bound").c_str());
    break;
  case CONTACT_TRESCA:
    PetscCheck(!setF, comm, PETSC_ERR_ARG_WRONG, "contact zone %d is Tresca: it takes %s (a stress), not %s", (int)z, r.Full(s + "slip_bound").c_str(), r.Full(s + "friction").c_str());
    PetscCheck(setg, comm, PETSC_ERR_ARG_WRONG, "Tresca contact zone %d needs %s g (the slip bound, a tangential stress)", (int)z, r.Full(s + "slip_bound").c_str());
    PetscCheck(g >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: the slip bound must be >= 0", r.Full(s + "slip_bound").c_str(), (double)g);
    zone.coef = g;
    break;
  case CONTACT_COULOMB:
    PetscCheck(!setg, comm, PETSC_ERR_ARG_WRONG, "contact zone %d is Coulomb: it takes %s, not %s", (int)z, r.Full(s + "friction").c_str(), r.Full(s + "slip_bound").c_str());
    PetscCheck(setF, comm, PETSC_ERR_ARG_WRONG, "Coulomb contact zone %d needs %s F (the friction coefficient)", (int)z, r.Full(s + "friction").c_str());
    PetscCheck(F >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: the friction coefficient must be >= 0", r.Full(s + "friction").c_str(), (double)F);
    zone.coef = F;
    break;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A physical surface name selects on a body from a mesh file only: on a box FACE is one of x0 ... z1 */
PetscErrorCode CheckBoxSelectors(MPI_Comm comm, const Scene_Impl &impl)
{
  std::vector<std::pair<const SceneSelector *, PetscInt>> all;

  PetscFunctionBegin;
  for (size_t b = 0; b < impl.bodies.size(); b++) {
    for (const SceneSupport &sp : impl.bodies[b].supports) all.emplace_back(&sp.selector, (PetscInt)b);
    for (const SceneTraction &t : impl.bodies[b].tractions) all.emplace_back(&t.selector, (PetscInt)b);
  }
  for (const SceneZoneSpec &z : impl.zones) {
    all.emplace_back(&z.face, z.zone.body);
    if (z.zone.type == CONTACT_ZONE_BODIES) all.emplace_back(&z.other, z.zone.other_body);
  }
  for (const auto &[sel, b] : all) {
    if (sel->face >= 0 || b < 0 || b >= (PetscInt)impl.bodies.size() || !impl.bodies[b].mesh.empty()) continue;
    PetscCheck(PETSC_FALSE, comm, PETSC_ERR_ARG_WRONG, "%s '%s': unknown face '%s' (body %d is a box: %s)", sel->option.c_str(), sel->text.c_str(), sel->name.c_str(), (int)b, SelectorUsage);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* every -<prefix>scene_* option must have been used by the parser */
PetscErrorCode CheckUnused(MPI_Comm comm, const char *prefix)
{
  PetscInt          n;
  char            **names, **values;
  const std::string stem = std::string(prefix ? prefix : "") + "scene_";
  std::string       bad, value;

  PetscFunctionBegin;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n && bad.empty(); i++) {
    const char *name = names[i][0] == '-' ? names[i] + 1 : names[i];
    if (!strncmp(name, stem.c_str(), stem.size())) {
      bad   = name;
      value = values[i] ? values[i] : "";
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(bad.empty(), comm, PETSC_ERR_ARG_WRONG,
             "unknown scene option -%s %s: no body or zone reads it (a misspelled name, or a body/zone index after a gap: bodies and zones are numbered 0, 1, 2, ... without gaps); run with "
             "-help for the scene options, or see docs/scenes.md",
             bad.c_str(), value.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* The physical volumes of a mesh read by FEMCreateDMPlexFromFile() (rank 0): the labels named after them and the
   values of "Cell Sets", for the message when -scene_body<b>_volume names none of them */
static PetscErrorCode VolumeNames(DM dm, std::string &list)
{
  PetscInt nlabels, cStart, cEnd;

  PetscFunctionBegin;
  list.clear();
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMGetNumLabels(dm, &nlabels));
  for (PetscInt l = 0; l < nlabels; l++) {
    const char     *name;
    DMLabel         label;
    IS              values;
    PetscInt        n;
    const PetscInt *v;
    PetscCall(DMGetLabelName(dm, l, &name));
    if (!strcmp(name, "depth") || !strcmp(name, "celltype")) continue;
    PetscCall(DMGetLabelByNum(dm, l, &label));
    PetscCall(DMLabelGetValueIS(label, &values));
    PetscCall(ISGetLocalSize(values, &n));
    PetscCall(ISGetIndices(values, &v));
    for (PetscInt i = 0; i < n; i++) {
      PetscInt first = -1;
      PetscCall(DMLabelGetStratumBounds(label, v[i], &first, NULL));
      if (first < cStart || first >= cEnd) continue; /* not cells (strata of a Gmsh label hold one dimension) */
      if (!strcmp(name, "Cell Sets")) list += (list.empty() ? "" : ", ") + ConeFETIFormat("%" PetscInt_FMT, v[i]);
      else if (i == 0) list += (list.empty() ? "" : ", ") + std::string(name);
    }
    PetscCall(ISRestoreIndices(values, &v));
    PetscCall(ISDestroy(&values));
  }
  if (list.empty()) list = "none";
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rank 0: the cells of the physical volume `volume` (a name, else a number of "Cell Sets") as their own mesh */
static PetscErrorCode RestrictToVolume(DM dm, const std::string &volume, const std::string &file, DM *sub, std::string &error)
{
  DMLabel  label = NULL;
  PetscInt value = 0, cStart, cEnd, ncells = 0;

  PetscFunctionBegin;
  *sub = NULL;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMGetLabel(dm, volume.c_str(), &label));
  if (label) {
    IS       values;
    PetscInt n;
    PetscCall(DMLabelGetValueIS(label, &values));
    PetscCall(ISGetLocalSize(values, &n));
    if (n == 1) PetscCall(ISGetMinMax(values, &value, NULL));
    else label = NULL;
    PetscCall(ISDestroy(&values));
  } else {
    char *end = nullptr;
    value     = (PetscInt)std::strtol(volume.c_str(), &end, 10);
    if (!volume.empty() && *end == 0) PetscCall(DMGetLabel(dm, "Cell Sets", &label));
  }
  if (label) {
    IS points;
    PetscCall(DMLabelGetStratumIS(label, value, &points));
    if (points) {
      PetscInt        n;
      const PetscInt *p;
      PetscCall(ISGetLocalSize(points, &n));
      PetscCall(ISGetIndices(points, &p));
      for (PetscInt i = 0; i < n; i++)
        if (p[i] >= cStart && p[i] < cEnd) ncells++;
      PetscCall(ISRestoreIndices(points, &p));
      PetscCall(ISDestroy(&points));
    }
  }
  if (!ncells) {
    std::string list;
    PetscCall(VolumeNames(dm, list));
    error = ConeFETIFormat("%s: no physical volume '%s' in the mesh (its volumes: %s)", file.c_str(), volume.c_str(), list.c_str());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(DMPlexFilter(dm, label, value, sub));
  PetscCall(PetscObjectSetName((PetscObject)*sub, file.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A body from a mesh file: read on rank 0 (FEMCreateDMPlexFromFile()), scaled and moved, restricted to a physical
   volume, added by FEMAddDMPlex(). names: the facet sets the body got (the physical surfaces), on every rank. */
static PetscErrorCode AddMeshBodyInner(MPI_Comm comm, FEM fem, const SceneBody &body, PetscInt *id, std::vector<std::string> &names)
{
  DM          dm = NULL, sub = NULL;
  PetscMPIInt rank;
  char        error[1024] = "";
  std::string joined;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(FEMCreateDMPlexFromFile(comm, body.mesh.c_str(), &dm));
  if (!rank) {
    std::string err;
    if (body.scale != 1 || body.translate[0] != 0 || body.translate[1] != 0 || body.translate[2] != 0) {
      Vec          X;
      PetscScalar *x;
      PetscInt     n;
      PetscCall(DMGetCoordinatesLocal(dm, &X));
      PetscCall(VecGetLocalSize(X, &n));
      PetscCall(VecGetArray(X, &x));
      for (PetscInt i = 0; i < n; i++) x[i] = body.scale * x[i] + body.translate[i % 3];
      PetscCall(VecRestoreArray(X, &x));
      PetscCall(DMSetCoordinatesLocal(dm, X));
    }
    if (!body.volume.empty()) PetscCall(RestrictToVolume(dm, body.volume, body.mesh, &sub, err));
    PetscCall(PetscStrncpy(error, err.c_str(), sizeof(error)));
  }
  PetscCallMPI(MPI_Bcast(error, sizeof(error), MPI_CHAR, 0, comm));
  if (error[0]) PetscCall(DMDestroy(&dm));
  PetscCheck(!error[0], comm, PETSC_ERR_ARG_WRONG, "%s", error);
  PetscCall(FEMAddDMPlex(fem, sub ? sub : dm, id));
  if (!rank) {
    PetscInt n;
    char   **list;
    PetscCall(FEMDMPlexGetFacetSetNames(sub ? sub : dm, &n, &list));
    for (PetscInt i = 0; i < n; i++) joined += std::string(i ? "\n" : "") + list[i];
    PetscCall(PetscStrArrayDestroy(&list));
  }
  PetscCall(DMDestroy(&sub));
  PetscCall(DMDestroy(&dm));
  {
    long len = (long)joined.size();
    PetscCallMPI(MPI_Bcast(&len, 1, MPI_LONG, 0, comm));
    if (rank) joined.assign((size_t)len, ' ');
    if (len) PetscCallMPI(MPI_Bcast(&joined[0], (PetscMPIInt)len, MPI_CHAR, 0, comm));
  }
  names.clear();
  for (size_t start = 0, end; !joined.empty() && start <= joined.size(); start = end + 1) {
    end = joined.find('\n', start);
    if (end == std::string::npos) end = joined.size();
    names.push_back(joined.substr(start, end - start));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The errors of reading and converting the mesh (the FEM layer's too: an inverted tetrahedron, a triangle of a
   facet set that is not on the boundary) name the option and the file, once */
static PetscErrorCode AddMeshBody(MPI_Comm comm, const char prefix[], FEM fem, const SceneBody &body, PetscInt b, PetscInt *id, std::vector<std::string> &names)
{
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = AddMeshBodyInner(comm, fem, body, id, names);
  PetscCall(PetscPopErrorHandler());
  if (ierr) {
    std::string why = ConeFETIErrorText(ierr);
    if (!why.compare(0, body.mesh.size() + 2, body.mesh + ": ")) why = why.substr(body.mesh.size() + 2);
    SETERRQ(comm, ierr, "-%sscene_body%d_mesh %s: %s", prefix ? prefix : "", (int)b, body.mesh.c_str(), why.c_str());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The FEM tag of a physical surface selector of mesh body b: the facet set whose name matches (spaces ignored:
   the options parser drops them), else an error listing the surfaces */
static PetscErrorCode ResolveSurface(MPI_Comm comm, const SceneBody &body, PetscInt b, const std::vector<std::string> &names, SceneSelector &sel)
{
  std::string list;

  PetscFunctionBegin;
  for (const std::string &n : names) {
    std::string compact;
    for (char c : n)
      if (c != ' ' && c != '\t') compact += c;
    if (compact == sel.name) {
      sel.name = n;
      if (sel.conditions.empty()) sel.tag = n;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    list += (list.empty() ? "" : ", ") + n;
  }
  SETERRQ(comm, PETSC_ERR_ARG_WRONG, "%s '%s': body %d's mesh %s has no physical surface '%s' (it has: %s; and the built-in x0 x1 y0 y1 z0 z1)", sel.option.c_str(), sel.text.c_str(), (int)b,
          body.mesh.c_str(), sel.name.c_str(), list.empty() ? "none" : list.c_str());
}

static PetscErrorCode ContactSceneReset(ContactScene scene)
{
  Scene_Impl &impl = *scene->impl;

  PetscFunctionBegin;
  PetscCall(ContactModelDestroy(&impl.cm));
  PetscCall(FEMDestroy(&impl.fem));
  impl.predicates.clear();
  impl.femsetup = impl.setup = impl.solved = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneCreate - Create an empty scene.

  Collective

  Input Parameter:
. comm - the communicator the model is solved on

  Output Parameter:
. scene - the scene

  Level: beginner

.seealso: `ContactSceneCreateFromOptions()`, `ContactSceneSetFromOptions()`, `ContactSceneSetUp()`, `ContactSceneDestroy()`
@*/
PetscErrorCode ContactSceneCreate(MPI_Comm comm, ContactScene *scene)
{
  ContactScene s;

  PetscFunctionBegin;
  PetscAssertPointer(scene, 2);
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscHeaderCreate(s, CONTACTSCENE_CLASSID, "ContactScene", "Contact scene from options", "ContactScene", comm, ContactSceneDestroy, ContactSceneView));
  PetscCallCXX(s->impl = new Scene_Impl());
  *scene = s;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A scene far beyond the machine stops here, in a second, with the estimate, rather than after minutes of meshing
   and assembly: the subdomain stiffness matrices (one triangle, about 20 nonzeros per dof on these meshes) and
   their sparse factors (FETIEstimateFactorMemory(); only for bodies whose decomposition the scene gives), against
   what all nodes have available (FETIGetMemoryBudget(), -feti_memory_budget per node). Deliberately a low
   estimate: FETISetUp() checks again, precisely, before its factorizations. */
template <class Full> static PetscErrorCode CheckMemory(MPI_Comm comm, const char prefix[], const Scene_Impl &impl, const Full &full)
{
  const double nnzperdof = 20;
  double       need = 0, dofs = 0, nsubs = 0, budget = 0;
  PetscReal    nodebudget;
  PetscBool    given;
  MPI_Comm     node;
  PetscMPIInt  noderank;

  PetscFunctionBegin;
  for (const SceneBody &body : impl.bodies) {
    double nodes = 1, nsub = 1;
    if (!body.mesh.empty()) continue; /* unknown before the file is read; FETISetUp() checks it */
    for (PetscInt d = 0; d < 3; d++) nodes *= (double)body.cells[d] * impl.refine + 1;
    if (body.decompositionset) nsub = body.decomposition == FEM_DECOMPOSITION_STRUCTURED ? (double)body.parts[0] * body.parts[1] * body.parts[2] : (double)body.parts[0];
    need += 3 * nodes * nnzperdof * 8.5; /* SBAIJ with 3x3 blocks: 8 bytes a value, an index per 9 */
    if (body.decompositionset) {
      PetscReal f, n = 3 * nodes / nsub;
      PetscCall(FETIEstimateFactorMemory(n, nnzperdof * n, &f));
      need += nsub * f;
    }
    dofs += 3 * nodes;
    nsubs += nsub;
  }
  PetscCall(FETIGetMemoryBudget(comm, prefix, &nodebudget, &given));
  if (nodebudget < 0) PetscFunctionReturn(PETSC_SUCCESS); /* the machine says nothing */
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_rank(node, &noderank));
  PetscCallMPI(MPI_Comm_free(&node));
  {
    double mine = noderank ? 0 : (double)nodebudget;
    PetscCallMPI(MPI_Allreduce(&mine, &budget, 1, MPI_DOUBLE, MPI_SUM, comm));
  }
  PetscCall(PetscInfo(NULL, "Scene memory estimate: %.1f MB (%.4g unknowns, %.4g subdomains); available on all nodes: %.1f MB\n", need / 1048576.0, dofs, nsubs, budget / 1048576.0));
  PetscCheck(need <= budget, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "The scene needs at least about %.1f MB (%.4g unknowns in %.4g subdomains: the stiffness matrices and their sparse factors, estimated), more than the %.1f MB %s; nothing was "
             "allocated. Reduce %s or the bodies' -scene_body<b>_cells, or use more subdomains (-scene_body<b>_subdomains: the factors shrink faster than the subdomains) or more nodes",
             need / 1048576.0, dofs, nsubs, budget / 1048576.0, given ? "that -feti_memory_budget (per node) allows" : "available (MemAvailable of the nodes)", full("-scene_refine").c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneCreateFromOptions - Create a scene and read it from the options database (`ContactSceneSetFromOptions()`).

  Collective

  Input Parameters:
+ comm   - the communicator
- prefix - options prefix (NULL for none): the scene reads -<prefix>scene_*, its model -<prefix>fem_*, -<prefix>feti_*, -<prefix>contact_*

  Output Parameter:
. scene - the scene, not yet set up

  Level: beginner

.seealso: `ContactSceneSetFromOptions()`, `ContactSceneSetUp()`
@*/
PetscErrorCode ContactSceneCreateFromOptions(MPI_Comm comm, const char prefix[], ContactScene *scene)
{
  PetscFunctionBegin;
  PetscCall(ContactSceneCreate(comm, scene));
  PetscCall(ContactSceneSetOptionsPrefix(*scene, prefix));
  PetscCall(ContactSceneSetFromOptions(*scene));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneDestroy - Destroy a scene with its model.

  Collective

  Input Parameter:
. scene - the scene

  Level: beginner

.seealso: `ContactSceneCreate()`
@*/
PetscErrorCode ContactSceneDestroy(ContactScene *scene)
{
  PetscFunctionBegin;
  if (!scene || !*scene) PetscFunctionReturn(PETSC_SUCCESS);
  PetscValidHeaderSpecific(*scene, CONTACTSCENE_CLASSID, 1);
  if (--((PetscObject)(*scene))->refct > 0) {
    *scene = NULL;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(ContactSceneReset(*scene));
  PetscCallCXX(delete (*scene)->impl);
  PetscCall(PetscHeaderDestroy(scene));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneSetOptionsPrefix - Set the prefix of the scene's options (-<prefix>scene_*); the model it builds gets the same prefix.

  Logically Collective

  Input Parameters:
+ scene  - the scene
- prefix - the prefix

  Level: intermediate

.seealso: `ContactSceneSetFromOptions()`
@*/
PetscErrorCode ContactSceneSetOptionsPrefix(ContactScene scene, const char prefix[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)scene, prefix));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneSetFromOptions - Read the scene from the options database (the schema is in docs/scenes.md).

  Collective

  Input Parameter:
. scene - the scene

  Options Database Keys:
+ -scene_name <name>                         - a name for the summary and the output
. -scene_refine <r>                          - multiply every box body's cells by r (mesh sizes of one scene; not for mesh files)
. -scene_view                                - view the scene after `ContactSceneSetUp()`
. -scene_body<b>_lower, _upper <x,y,z>       - corners of box b (bodies are numbered 0, 1, ... without gaps)
. -scene_body<b>_cells <nx,ny,nz>            - hexahedra along each axis (each cut into 6 tetrahedra)
. -scene_body<b>_mesh <file>                 - or a mesh file of tetrahedra (Gmsh .msh 2.2/4.x, any DMPlexCreateFromFile() format)
. -scene_body<b>_scale <s>, _translate <x,y,z> - mesh: coordinates x become s x + t
. -scene_body<b>_volume <name or number>     - mesh: only the cells of this physical volume
. -scene_body<b>_E, _nu                      - material (default -fem_E, -fem_nu, else steel)
. -scene_body<b>_decomposition <structured,metis> - how the body is cut into subdomains
. -scene_body<b>_subdomains <px,py,pz or n>  - subdomains (structured: per axis; metis: a count)
. -scene_body<b>_fix <sel,...>               - faces (or parts) with u = 0; _fix_x, _fix_y, _fix_z fix one component
. -scene_body<b>_displace<k>_face <sel,...>  - faces (or parts) moved by displacement k (k = 0, 1, ...)
. -scene_body<b>_displace<k>_value <ux,uy,uz> - displacement k, every component; or only some: _displace<k>_x <ux>, _y, _z
. -scene_body<b>_traction_<face> <tx,ty,tz>  - traction on a whole face x0 x1 y0 y1 z0 z1
. -scene_body<b>_traction<k>_face <sel>      - traction k on part of a face, with -scene_body<b>_traction<k>_value <tx,ty,tz>
. -scene_body<b>_force <fx,fy,fz>            - volume force density (none when not given)
. -scene_zone<z>_type <foundation,bodies>    - contact zone z: a rigid obstacle or another body
. -scene_zone<z>_body, _face <b>, <sel>      - the body and face (part) that may touch
. -scene_zone<z>_shape <plane,sphere,cylinder> - foundation: the obstacle's shape (the body lies outside it)
. -scene_zone<z>_point, _normal <x,y,z>      - foundation, plane: the plane (normal toward the body)
. -scene_zone<z>_center <x,y,z>, _radius <R> - foundation, sphere: center and radius; cylinder: a point of the axis and radius
. -scene_zone<z>_axis <ax,ay,az>             - foundation, cylinder: the axis direction
. -scene_zone<z>_other_body, _other_face     - bodies: the other body and its face
. -scene_zone<z>_slave <finer,body,other>    - bodies: the slave face, paired node to surface with the other (master) face
. -scene_zone<z>_search_distance <d>         - bodies: slave nodes farther than d from the master face are not contact nodes (default: its longest edge)
- -scene_zone<z>_law <frictionless,tresca,coulomb> - with -scene_zone<z>_slip_bound <g> (Tresca, a stress) or -scene_zone<z>_friction <F> (Coulomb)

  Notes:
  A face selector is FACE or FACE/COND[/COND...]: FACE one of x0 x1 y0 y1 z0 z1 (x = lower x, x = upper x, ...;
  on a mesh body the triangles facing mostly that way) or, on a mesh body, a physical surface of the file (its name,
  or its number), COND a condition AXIS OP VALUE (OP one of < <= > >=) on the centroids of the face's triangles; e.g. z0/x>1 is
  the part of the bottom face beyond x = 1. Quote selectors on the command line ('z0/x>1').

  Dirichlet conditions enter FETI as the model's option -fem_dirichlet says (multipliers: Total FETI, the
  default; primal: kept in the primal space). Any -scene_* option that no body or zone reads is an error.

  Level: beginner

.seealso: `ContactSceneSetUp()`, `ContactSceneView()`
@*/
PetscErrorCode ContactSceneSetFromOptions(ContactScene scene)
{
  Scene_Impl &impl = *scene->impl;
  const char *prefix;
  MPI_Comm    comm;
  PetscBool   help, set;
  char        name[256];

  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  comm = PetscObjectComm((PetscObject)scene);
  PetscCall(ContactSceneReset(scene));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)scene, &prefix));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscCall(PetscStrncpy(name, impl.name.c_str(), sizeof(name)));
  PetscBool refineset = PETSC_FALSE;
  PetscObjectOptionsBegin((PetscObject)scene);
  Reader r{PetscOptionsObject, prefix, comm, help};
  PetscCall(PetscOptionsString("-scene_name", "Name of the scene (summary, output)", "ContactSceneSetFromOptions", name, name, sizeof(name), &set));
  PetscCheck(strlen(name) < sizeof(name) - 1, comm, PETSC_ERR_ARG_SIZ, "-scene_name: at most %d characters", (int)sizeof(name) - 2); /* PETSc cuts longer strings */
  PetscCall(r.Int("-scene_refine", "Multiply every box body's cells by this factor", "a positive integer", &impl.refine, &refineset));
  PetscCheck(impl.refine >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %" PetscInt_FMT ": the refinement factor must be a positive integer", r.Full("-scene_refine").c_str(), impl.refine);
  PetscCall(PetscOptionsName("-scene_view", "View the scene after ContactSceneSetUp()", "ContactSceneView", &set));
  impl.bodies.clear();
  impl.zones.clear();
  for (PetscInt b = 0;; b++) {
    PetscBool exists;
    SceneBody body;
    PetscCall(AnySet(r, ConeFETIFormat("-scene_body%d_", (int)b), {"lower", "upper", "cells", "mesh"}, &exists));
    if (!exists && !(help && b == 0)) break;
    PetscCall(ReadBody(r, b, exists, body));
    if (exists) PetscCallCXX(impl.bodies.push_back(body));
    if (!exists) break;
  }
  for (PetscInt z = 0;; z++) {
    PetscBool     exists;
    SceneZoneSpec spec;
    PetscCall(AnySet(r, ConeFETIFormat("-scene_zone%d_", (int)z), {"face", "law", "type"}, &exists));
    if (!exists && !(help && z == 0)) break;
    PetscCall(ReadZone(r, z, exists, (PetscInt)impl.bodies.size(), spec));
    if (exists) PetscCallCXX(impl.zones.push_back(spec));
    if (!exists) break;
  }
  PetscOptionsEnd();
  if (refineset && impl.refine > 1) {
    /* it multiplies box cells only: on a scene of mesh files it would change nothing, without a word */
    bool box = false;
    for (const SceneBody &body : impl.bodies) box = box || body.mesh.empty();
    PetscCheck(
        box || impl.bodies.empty(), comm, PETSC_ERR_ARG_WRONG,
        "%s %" PetscInt_FMT
        ": every body of the scene comes from a mesh file, and the refinement multiplies the cells of box bodies only; refine the mesh where it was made (in Gmsh: -clscale or Mesh.MeshSizeFactor)",
        ("-" + std::string(prefix ? prefix : "") + "scene_refine").c_str(), impl.refine);
  }
  impl.name = name;
  PetscCall(CheckUnused(comm, prefix));
  PetscCall(CheckBoxSelectors(comm, impl));
  /* mesh sizes after refinement, and subdomain counts that fit them. The sizes are counted in floating point:
     the products of the refined cell counts can overflow any integer type */
  const auto full  = [&](const std::string &name) { return "-" + std::string(prefix ? prefix : "") + name.substr(1); };
  double     total = 0; /* unknowns of all bodies: the FEM numbers them together */
  for (size_t b = 0; b < impl.bodies.size(); b++) {
    SceneBody &body = impl.bodies[b];
    if (!body.mesh.empty()) continue; /* its size is known when the file is read */
    double            c[3], nodes = 1, tets = 6;
    const std::string opt   = full(ConeFETIFormat("-scene_body%d_cells", (int)b));
    std::string       given = ConeFETIFormat("%s %" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT, opt.c_str(), body.cells[0], body.cells[1], body.cells[2]);
    if (impl.refine > 1) given += ConeFETIFormat(" with %s %" PetscInt_FMT, full("-scene_refine").c_str(), impl.refine);
    for (PetscInt d = 0; d < 3; d++) {
      c[d] = (double)body.cells[d] * impl.refine;
      nodes *= c[d] + 1;
      tets *= c[d];
    }
    total += 3 * nodes;
    PetscCheck(3 * nodes <= PETSC_MAX_INT && tets <= PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s: body %d's mesh of %.4g x %.4g x %.4g cells has %.4g unknowns and %.4g tetrahedra: it does not fit %d-bit PetscInt indices (at most %" PetscInt_FMT "); reduce %s", given.c_str(),
               (int)b, c[0], c[1], c[2], 3 * nodes, tets, (int)(8 * sizeof(PetscInt)), (PetscInt)PETSC_MAX_INT, (impl.refine > 1 ? full("-scene_refine") + " or " + opt : opt).c_str());
    if (!body.decompositionset) continue;
    if (body.decomposition == FEM_DECOMPOSITION_STRUCTURED)
      for (PetscInt d = 0; d < 3; d++)
        PetscCheck(body.parts[d] <= body.cells[d] * impl.refine, comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-%sscene_body%d_subdomains: %" PetscInt_FMT " subdomains along %c but the body has %" PetscInt_FMT " cells there", prefix ? prefix : "", (int)b, body.parts[d], (char)('x' + d),
                   body.cells[d] * impl.refine);
    else
      PetscCheck(body.parts[0] <= tets, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sscene_body%d_subdomains: %" PetscInt_FMT " METIS subdomains but the body has %lld tetrahedra", prefix ? prefix : "", (int)b,
                 body.parts[0], (long long)tets);
  }
  PetscCheck(total <= PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "the scene's %d bodies have %.4g unknowns together: they do not fit %d-bit PetscInt indices (at most %" PetscInt_FMT "); reduce %s or the bodies' -scene_body<b>_cells",
             (int)impl.bodies.size(), total, (int)(8 * sizeof(PetscInt)), (PetscInt)PETSC_MAX_INT, full("-scene_refine").c_str());
  PetscCall(CheckMemory(comm, prefix, impl, full));
  impl.fromoptions = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneSetUpFEM - Build only the scene's finite element model: mesh and decompose the bodies, tag the faces of
  supports, tractions and contact zones, and set up the `FEM`; no contact model, no FETI operator.

  Collective

  Input Parameter:
. scene - the scene, read by `ContactSceneSetFromOptions()`

  Notes:
  For a program that solves the scene's mesh another way (e.g. `tutorials/feti/gamg.cxx`: CG + GAMG on the assembled
  stiffness) without paying for the FETI set-up. `ContactSceneSetUp()` calls it first when it has not been called;
  calling it again does nothing.

  Level: intermediate

.seealso: `ContactSceneSetUp()`, `ContactSceneGetFEM()`, `FEMAssembleGlobal()`
@*/
PetscErrorCode ContactSceneSetUpFEM(ContactScene scene)
{
  Scene_Impl &impl = *scene->impl;
  MPI_Comm    comm;
  const char *prefix;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  if (impl.femsetup) PetscFunctionReturn(PETSC_SUCCESS);
  comm = PetscObjectComm((PetscObject)scene);
  PetscCheck(
      !impl.bodies.empty(), comm, PETSC_ERR_ARG_WRONGSTATE,
      "the scene has no body: give one with -scene_body0_lower, -scene_body0_upper and -scene_body0_cells, or -scene_body0_mesh (e.g. -options_file petsc-options/brick.opts; see docs/scenes.md)");
  {
    /* every rank needs a subdomain: say which scene options to change (METIS may add subdomains, never remove them) */
    PetscMPIInt size;
    PetscInt64  nsub = 0;
    PetscBool   all  = PETSC_TRUE;
    PetscCallMPI(MPI_Comm_size(comm, &size));
    for (const SceneBody &body : impl.bodies) {
      if (!body.decompositionset) all = PETSC_FALSE;
      nsub += (PetscInt64)body.parts[0] * body.parts[1] * body.parts[2];
    }
    PetscCheck(!all || nsub >= size, comm, PETSC_ERR_ARG_SIZ, "the scene has %lld subdomains for %d MPI ranks: every rank needs one; raise -scene_body<b>_subdomains or run on fewer ranks",
               (long long)nsub, (int)size);
  }
  for (PetscLogDouble &t : impl.time_phases) t = 0;
  impl.progress.fn  = ContactSceneProgress_Private; /* sceneprogress.cxx */
  impl.progress.ctx = scene;
  PetscCall(ConeFETIProgressBegin_Private(impl.progress, CONEFETI_PHASE_MESH, 0));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)scene, &prefix));
  PetscCall(FEMCreate(comm, &impl.fem));
  PetscCall(FEMSetOptionsPrefix(impl.fem, prefix));
  for (size_t bi = 0; bi < impl.bodies.size(); bi++) {
    SceneBody                   &body = impl.bodies[bi];
    const PetscInt               b    = (PetscInt)bi;
    PetscInt                     cells[3], id;
    std::set<std::string>        tagged;
    std::vector<SceneSelector *> selectors;

    std::vector<std::string> surfaces; /* a mesh body's physical surfaces */

    if (body.mesh.empty()) {
      for (PetscInt d = 0; d < 3; d++) cells[d] = body.cells[d] * impl.refine;
      PetscCall(FEMAddBox(impl.fem, body.lower.data(), body.upper.data(), cells, &id));
    } else PetscCall(AddMeshBody(comm, prefix, impl.fem, body, b, &id, surfaces));
    PetscCall(FEMSetMaterial(impl.fem, id, body.E, body.nu));
    if (body.decompositionset) PetscCall(FEMSetDecomposition(impl.fem, id, body.decomposition, body.parts.data()));
    /* the parts of faces become boundary tags, one per distinct selector */
    for (SceneSupport &sp : body.supports) selectors.push_back(&sp.selector);
    for (SceneTraction &t : body.tractions) selectors.push_back(&t.selector);
    for (SceneZoneSpec &z : impl.zones) {
      if (z.zone.body == b) selectors.push_back(&z.face);
      if (z.zone.type == CONTACT_ZONE_BODIES && z.zone.other_body == b) selectors.push_back(&z.other);
    }
    for (SceneSelector *sel : selectors) {
      if (sel->face < 0) PetscCall(ResolveSurface(comm, body, b, surfaces, *sel));
      PetscCheck(sel->tag.size() < sizeof(((ContactZone *)0)->face), comm, PETSC_ERR_ARG_WRONG, "%s '%s': the selector is too long (at most %d characters)", sel->option.c_str(), sel->text.c_str(),
                 (int)sizeof(((ContactZone *)0)->face) - 1);
      if (sel->conditions.empty() || tagged.count(sel->tag)) continue;
      PetscCallCXX(impl.predicates.push_back(std::make_unique<SceneSelector>(*sel)));
      /* part of a physical surface: its triangles that meet the conditions; part of a box face: the boundary
         triangles facing that way that meet them */
      if (sel->face < 0) PetscCall(FEMTagFacesWithin(impl.fem, id, sel->tag.c_str(), sel->name.c_str(), SelectorPredicate, impl.predicates.back().get()));
      else PetscCall(FEMTagFaces(impl.fem, id, sel->tag.c_str(), SelectorPredicate, impl.predicates.back().get()));
      tagged.insert(sel->tag);
    }
    for (const SceneSupport &sp : body.supports) {
      const PetscBool comps[3] = {(sp.mask & 1u) ? PETSC_TRUE : PETSC_FALSE, (sp.mask & 2u) ? PETSC_TRUE : PETSC_FALSE, (sp.mask & 4u) ? PETSC_TRUE : PETSC_FALSE};
      PetscCall(FEMSetDisplacement(impl.fem, id, sp.selector.tag.c_str(), comps, sp.value.data()));
    }
    for (const SceneTraction &t : body.tractions) PetscCall(FEMSetTraction(impl.fem, id, t.selector.tag.c_str(), t.value.data()));
    if (body.hasforce) PetscCall(FEMSetBodyForce(impl.fem, id, ConstantForce, body.force.data()));
  }
  PetscCall(FEMSetFromOptions(impl.fem));
  PetscCall(FEMSetUp(impl.fem));
  /* every selector must select something */
  for (size_t b = 0; b < impl.bodies.size(); b++) {
    std::vector<const SceneSelector *> selectors;
    for (const SceneSupport &sp : impl.bodies[b].supports) selectors.push_back(&sp.selector);
    for (const SceneTraction &t : impl.bodies[b].tractions) selectors.push_back(&t.selector);
    for (const SceneZoneSpec &z : impl.zones) {
      if (z.zone.body == (PetscInt)b) selectors.push_back(&z.face);
      if (z.zone.type == CONTACT_ZONE_BODIES && z.zone.other_body == (PetscInt)b) selectors.push_back(&z.other);
    }
    for (const SceneSelector *sel : selectors) {
      PetscInt         n;
      const SceneBody &body = impl.bodies[b];
      PetscCall(FEMGetTaggedNodes(impl.fem, (PetscInt)b, sel->tag.c_str(), &n, NULL, NULL, NULL));
      if (!body.mesh.empty())
        PetscCheck(n > 0, comm, PETSC_ERR_ARG_WRONG,
                   "%s '%s' selects no boundary triangle of body %d, the mesh %s (conditions apply to triangle centroids; a surface between two volumes of the mesh is no boundary: make a body of "
                   "each with -scene_body<b>_volume)",
                   sel->option.c_str(), sel->text.c_str(), (int)b, body.mesh.c_str());
      PetscCheck(n > 0, comm, PETSC_ERR_ARG_WRONG, "%s '%s' selects no boundary triangle of body %d, the box [%g,%g]x[%g,%g]x[%g,%g] (conditions apply to triangle centroids)", sel->option.c_str(),
                 sel->text.c_str(), (int)b, (double)body.lower[0], (double)body.upper[0], (double)body.lower[1], (double)body.upper[1], (double)body.lower[2], (double)body.upper[2]);
    }
  }
  PetscCall(ConeFETIProgressEnd_Private(impl.progress)); /* records the mesh phase's duration (sceneprogress.cxx) */
  impl.femsetup = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneSetUp - Build the scene's model: mesh and decompose the bodies, set up the FEM, add the contact zones,
  and set up the `ContactModel` (FETI operators, factorizations, the dual contact problem).

  Collective

  Input Parameter:
. scene - the scene, read by `ContactSceneSetFromOptions()`

  Notes:
  Only what the scene calls for is built: tractions on the faces given, a volume force only when given, contact
  rows only for the zones given (no zone: the linear FETI pipeline).

  Level: beginner

.seealso: `ContactSceneSolve()`, `ContactSceneSetUpFEM()`, `ContactSceneGetFEM()`, `ContactSceneGetContactModel()`
@*/
PetscErrorCode ContactSceneSetUp(ContactScene scene)
{
  Scene_Impl    &impl = *scene->impl;
  PetscLogDouble t0, t1;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  if (impl.setup) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(CONTACTSCENE_SetUp, scene, 0, 0, 0));
  PetscCall(ContactSceneSetUpFEM(scene));
  PetscCall(PetscTime(&t0));
  PetscCall(ContactModelCreate(impl.fem, &impl.cm));
  PetscCall(ContactModelSetProgress(impl.cm, ContactSceneProgress_Private, scene));
  for (SceneZoneSpec &z : impl.zones) {
    PetscCall(PetscStrncpy(z.zone.face, z.face.tag.c_str(), sizeof(z.zone.face)));
    if (z.zone.type == CONTACT_ZONE_BODIES) PetscCall(PetscStrncpy(z.zone.other_face, z.other.tag.c_str(), sizeof(z.zone.other_face)));
    PetscCall(ContactModelAddZone(impl.cm, &z.zone));
  }
  PetscCall(ContactModelSetUp(impl.cm));
  PetscCall(PetscTime(&t1));
  impl.time_setup = impl.time_phases[CONEFETI_PHASE_MESH] + (t1 - t0);
  impl.setup      = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(CONTACTSCENE_SetUp, scene, 0, 0, 0));
  PetscCall(PetscObjectViewFromOptions((PetscObject)scene, NULL, "-scene_view"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneSolve - Solve the scene: the pipeline its zones call for, then the primal solution.

  Collective

  Input Parameter:
. scene - the scene (set up on demand)

  Notes:
  The solve always ends with a stated reason (`ContactSceneGetSummary()`): converged, not converged within the
  iteration limits, or no equilibrium (loads that supports and friction cannot carry). It does not raise an
  error in those cases; check `ContactSceneSummary`.converged.

  Level: beginner

.seealso: `ContactSceneSetUp()`, `ContactSceneGetSummary()`, `ContactSceneWriteOutput()`
@*/
PetscErrorCode ContactSceneSolve(ContactScene scene)
{
  Scene_Impl    &impl = *scene->impl;
  PetscLogDouble t0, t1;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  PetscCall(ContactSceneSetUp(scene));
  PetscCall(PetscLogEventBegin(CONTACTSCENE_Solve, scene, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCall(ContactModelSolve(impl.cm));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogEventEnd(CONTACTSCENE_Solve, scene, 0, 0, 0));
  impl.time_solve = t1 - t0;
  impl.solved     = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneView - Describe the scene: bodies, supports, loads, contact zones (and the model after setup).

  Collective

  Input Parameters:
+ scene  - the scene
- viewer - an ASCII viewer (NULL: stdout)

  Options Database Key:
. -scene_view - view after `ContactSceneSetUp()`

  Level: beginner

.seealso: `ContactSceneSetFromOptions()`
@*/
PetscErrorCode ContactSceneView(ContactScene scene, PetscViewer viewer)
{
  Scene_Impl &impl = *scene->impl;
  PetscBool   ascii;
  PetscMPIInt size;
  std::string text;
  const char *prefix;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(PetscObjectComm((PetscObject)scene), &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)scene), &size));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)scene, &prefix));
  /* the lines are formatted here (C printf: plain %g) and printed whole */
  text = ConeFETIFormat("ContactScene Object: %s%s%s%d MPI process%s\n", prefix ? "(" : "", prefix ? prefix : "", prefix ? ") " : "", (int)size, size > 1 ? "es" : "");
  text += ConeFETIFormat("  scene \"%s\": %d bod%s, %d contact zone%s, refinement %d\n", impl.name.c_str(), (int)impl.bodies.size(), impl.bodies.size() == 1 ? "y" : "ies", (int)impl.zones.size(),
                         impl.zones.size() == 1 ? "" : "s", (int)impl.refine);
  for (size_t b = 0; b < impl.bodies.size(); b++) {
    const SceneBody &body = impl.bodies[b];
    if (!body.mesh.empty()) {
      text += ConeFETIFormat("  body %d: mesh %s", (int)b, body.mesh.c_str());
      if (!body.volume.empty()) text += ConeFETIFormat(", volume %s", body.volume.c_str());
      if (body.scale != 1) text += ConeFETIFormat(", scaled by %g", (double)body.scale);
      if (body.translate[0] != 0 || body.translate[1] != 0 || body.translate[2] != 0)
        text += ConeFETIFormat(", moved by (%g, %g, %g)", (double)body.translate[0], (double)body.translate[1], (double)body.translate[2]);
      text += ConeFETIFormat(", E %g, nu %g", (double)body.E, (double)body.nu);
    } else
      text += ConeFETIFormat("  body %d: box [%g,%g]x[%g,%g]x[%g,%g], %dx%dx%d cells, E %g, nu %g", (int)b, (double)body.lower[0], (double)body.upper[0], (double)body.lower[1], (double)body.upper[1],
                             (double)body.lower[2], (double)body.upper[2], (int)(body.cells[0] * impl.refine), (int)(body.cells[1] * impl.refine), (int)(body.cells[2] * impl.refine), (double)body.E,
                             (double)body.nu);
    if (body.decompositionset) {
      if (body.decomposition == FEM_DECOMPOSITION_STRUCTURED) text += ConeFETIFormat(", structured %dx%dx%d subdomains", (int)body.parts[0], (int)body.parts[1], (int)body.parts[2]);
      else text += ConeFETIFormat(", METIS %d subdomains", (int)body.parts[0]);
    }
    text += "\n";
    for (const SceneSupport &sp : body.supports) {
      if (sp.displace < 0) text += ConeFETIFormat("    support %s: u%s%s%s = 0\n", sp.selector.text.c_str(), (sp.mask & 1u) ? "x" : "", (sp.mask & 2u) ? "y" : "", (sp.mask & 4u) ? "z" : "");
      else {
        text += ConeFETIFormat("    displacement %d on %s:", (int)sp.displace, sp.selector.text.c_str());
        for (PetscInt c = 0; c < 3; c++) text += (sp.mask & (1u << c)) ? ConeFETIFormat(" u%c = %g", (char)('x' + c), (double)sp.value[c]) : ConeFETIFormat(" u%c free", (char)('x' + c));
        text += "\n";
      }
    }
    for (const SceneTraction &t : body.tractions) text += ConeFETIFormat("    traction on %s: (%g, %g, %g)\n", t.selector.text.c_str(), (double)t.value[0], (double)t.value[1], (double)t.value[2]);
    if (body.hasforce) text += ConeFETIFormat("    volume force (%g, %g, %g)\n", (double)body.force[0], (double)body.force[1], (double)body.force[2]);
  }
  for (size_t z = 0; z < impl.zones.size(); z++) {
    const ContactZone &zn = impl.zones[z].zone;
    const std::string  law =
        zn.law == CONTACT_FRICTIONLESS ? std::string("frictionless") : ConeFETIFormat("%s %s %g", ContactLaws[zn.law], zn.law == CONTACT_TRESCA ? "slip bound" : "F", (double)zn.coef);
    if (zn.type == CONTACT_ZONE_FOUNDATION && zn.shape == CONTACT_OBSTACLE_SPHERE)
      text += ConeFETIFormat("  zone %d: body %d face %s on the rigid sphere with center (%g, %g, %g) and radius %g, %s\n", (int)z, (int)zn.body, impl.zones[z].face.text.c_str(), (double)zn.center[0],
                             (double)zn.center[1], (double)zn.center[2], (double)zn.radius, law.c_str());
    else if (zn.type == CONTACT_ZONE_FOUNDATION && zn.shape == CONTACT_OBSTACLE_CYLINDER)
      text += ConeFETIFormat("  zone %d: body %d face %s on the rigid cylinder with axis through (%g, %g, %g) along (%g, %g, %g) and radius %g, %s\n", (int)z, (int)zn.body,
                             impl.zones[z].face.text.c_str(), (double)zn.center[0], (double)zn.center[1], (double)zn.center[2], (double)zn.axis[0], (double)zn.axis[1], (double)zn.axis[2],
                             (double)zn.radius, law.c_str());
    else if (zn.type == CONTACT_ZONE_FOUNDATION)
      text += ConeFETIFormat("  zone %d: body %d face %s on the rigid plane through (%g, %g, %g) with normal (%g, %g, %g), %s\n", (int)z, (int)zn.body, impl.zones[z].face.text.c_str(),
                             (double)zn.point[0], (double)zn.point[1], (double)zn.point[2], (double)zn.normal[0], (double)zn.normal[1], (double)zn.normal[2], law.c_str());
    else
      text += ConeFETIFormat("  zone %d: body %d face %s against body %d face %s (node to surface, slave %s, search distance %s), %s\n", (int)z, (int)zn.body, impl.zones[z].face.text.c_str(),
                             (int)zn.other_body, impl.zones[z].other.text.c_str(), ContactZoneSlaves[zn.slave],
                             zn.search_distance > 0 ? ConeFETIFormat("%g", (double)zn.search_distance).c_str() : "the master's longest edge", law.c_str());
  }
  for (size_t start = 0, end; start < text.size(); start = end + 1) { /* line by line: the viewer's tab applies to each */
    end = text.find('\n', start);
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s\n", text.substr(start, end - start).c_str()));
  }
  if (impl.setup) {
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(FEMView(impl.fem, viewer));
    PetscCall(ContactModelView(impl.cm, viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneGetName - The scene's name (-scene_name).

  Not Collective

  Input Parameter:
. scene - the scene

  Output Parameter:
. name - the name (do not free)

  Level: beginner

.seealso: `ContactSceneSetFromOptions()`
@*/
PetscErrorCode ContactSceneGetName(ContactScene scene, const char **name)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  *name = scene->impl->name.c_str();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneGetFEM - The scene's finite element model (after `ContactSceneSetUp()` or `ContactSceneSetUpFEM()`).

  Not Collective

  Input Parameter:
. scene - the scene

  Output Parameter:
. fem - the model (do not destroy)

  Level: beginner

.seealso: `ContactSceneGetContactModel()`
@*/
PetscErrorCode ContactSceneGetFEM(ContactScene scene, FEM *fem)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  PetscCheck(scene->impl->femsetup, PetscObjectComm((PetscObject)scene), PETSC_ERR_ORDER, "Call ContactSceneSetUp() or ContactSceneSetUpFEM() first");
  *fem = scene->impl->fem;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneGetContactModel - The scene's contact model (after `ContactSceneSetUp()`; set up).

  Not Collective

  Input Parameter:
. scene - the scene

  Output Parameter:
. cm - the contact model (do not destroy)

  Level: beginner

.seealso: `ContactSceneGetFEM()`
@*/
PetscErrorCode ContactSceneGetContactModel(ContactScene scene, ContactModel *cm)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  PetscCheck(scene->impl->setup, PetscObjectComm((PetscObject)scene), PETSC_ERR_ORDER, "Call ContactSceneSetUp() first");
  *cm = scene->impl->cm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactSceneGetBodyMaterial - The material of a body of the scene.

  Not Collective

  Input Parameters:
+ scene - the scene
- body  - the body

  Output Parameters:
+ E  - Young's modulus
- nu - Poisson's ratio

  Level: intermediate

.seealso: `ContactSceneSetFromOptions()`
@*/
PetscErrorCode ContactSceneGetBodyMaterial(ContactScene scene, PetscInt body, PetscReal *E, PetscReal *nu)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  PetscCheck(body >= 0 && body < (PetscInt)scene->impl->bodies.size(), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Body %" PetscInt_FMT " does not exist (the scene has %d)", body,
             (int)scene->impl->bodies.size());
  if (E) *E = scene->impl->bodies[body].E;
  if (nu) *nu = scene->impl->bodies[body].nu;
  PetscFunctionReturn(PETSC_SUCCESS);
}
