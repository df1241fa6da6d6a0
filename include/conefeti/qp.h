/* Layer qp: quadratic programming solvers on PETSc Mat/Vec. */
#pragma once

#include <petscksp.h>
#include <petsctao.h>
