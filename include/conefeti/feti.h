/* Layer feti: FETI operators (F, G, projector, generalized inverse) as MATSHELLs from subdomain data. */
#pragma once

#include <petscksp.h>
