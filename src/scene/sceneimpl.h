/* Private structures of the scene layer (ContactScene: options, summary, output), shared between the files of src/scene. */
#pragma once

#include <petsc/private/petscimpl.h>
#include <conefeti/sys.h>
#include <conefeti/io.h>
#include <conefeti/compat.h>
#include <conefeti/private/progress.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

/* A part of a box face: the built-in face and conditions on the centroid of its boundary triangles,
   written FACE[/AXIS OP VALUE]..., e.g. "z0/x>1" (docs/scenes.md); on a mesh body FACE may also be a
   physical surface of the mesh file (a facet set of the body, FEMAddDMPlex()). */
struct SceneCondition {
  PetscInt  axis;    /* 0, 1, 2 */
  PetscBool greater; /* > or >= (else < or <=) */
  PetscBool equal;   /* >= or <= */
  PetscReal value;
};

struct SceneSelector {
  std::string                 text;      /* as given */
  std::string                 option;    /* the option it came from, for messages */
  PetscInt                    face = -1; /* x0 ... z1, or -1: the physical surface `name` */
  std::string                 name;      /* as written (spaces removed); after setup the facet set's own name */
  std::vector<SceneCondition> conditions;
  std::string                 tag; /* the FEM boundary tag it becomes */
};

/* A Dirichlet condition: a clamped face (-scene_body<b>_fix, _fix_x, ...) or a displaced one (_displace<k>_*) */
struct SceneSupport {
  SceneSelector            selector;
  unsigned                 mask;          /* bit c: component c prescribed */
  std::array<PetscReal, 3> value{};       /* the prescribed displacement (0 for _fix) */
  PetscInt                 displace = -1; /* k of -scene_body<b>_displace<k>_*, or -1 for _fix */
  std::string              kind;          /* "fix", "fix_x", ..., "displace<k>": the option's stem, for the summary */
};

struct SceneTraction {
  SceneSelector            selector;
  std::array<PetscReal, 3> value{}; /* zero: also the default -help shows */
};

struct SceneBody {
  std::string                mesh;      /* a mesh file (-scene_body<b>_mesh), else a box */
  PetscReal                  scale = 1; /* mesh: x -> scale x + translate */
  std::array<PetscReal, 3>   translate{};
  std::string                volume; /* mesh: only the cells of this physical volume (name or number) */
  std::array<PetscReal, 3>   lower{}, upper{};
  std::array<PetscInt, 3>    cells{};
  PetscReal                  E = 2.12e11, nu = 0.277;
  PetscBool                  decompositionset = PETSC_FALSE;
  FEMDecompositionType       decomposition    = FEM_DECOMPOSITION_STRUCTURED;
  std::array<PetscInt, 3>    parts{1, 1, 1};
  std::vector<SceneSupport>  supports;
  std::vector<SceneTraction> tractions;
  PetscBool                  hasforce = PETSC_FALSE;
  std::array<PetscReal, 3>   force{};
};

struct SceneZoneSpec {
  ContactZone   zone{};
  SceneSelector face, other;
};

struct Scene_Impl {
  std::string                                 name   = "scene";
  PetscInt                                    refine = 1;
  std::vector<SceneBody>                      bodies;
  std::vector<SceneZoneSpec>                  zones;
  std::vector<std::unique_ptr<SceneSelector>> predicates; /* contexts of the FEM tag predicates (stable addresses) */
  PetscBool                                   fromoptions = PETSC_FALSE, femsetup = PETSC_FALSE, setup = PETSC_FALSE, solved = PETSC_FALSE;
  FEM                                         fem        = nullptr;
  ContactModel                                cm         = nullptr;
  PetscLogDouble                              time_setup = 0, time_solve = 0; /* time_setup includes the mesh phase (time_phases) */
  /* progress (sceneprogress.cxx): the caller's hook, the scene's own reports (the mesh phase), and the
     duration of each phase on this rank, which the summary reports */
  ConeFETIProgressFn progressfn  = nullptr;
  void              *progressctx = nullptr;
  ConeFETIProgress   progress;
  PetscLogDouble     time_phases[CONEFETI_PHASE_COUNT] = {};
};

/* the hook the scene sets on itself and its ContactModel: records the phase durations, then calls the caller's */
PETSC_INTERN PetscErrorCode ContactSceneProgress_Private(const ConeFETIProgressInfo *, void *);

struct _SceneOps {
  PetscErrorCode (*unused)(void);
};

struct _p_ContactScene {
  PETSCHEADER(struct _SceneOps);
  Scene_Impl *impl;
};

PETSC_INTERN const char *const SceneFaceNames[6];
