// PLACEHOLDER
#include "problems/io/siconos_format.h"
