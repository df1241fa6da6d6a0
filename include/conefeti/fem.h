/* Layer fem: structured tetrahedral meshes, P1 elasticity, decomposition, constraint rows. */
#pragma once

#include <petscmat.h>
