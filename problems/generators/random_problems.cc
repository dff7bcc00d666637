// PLACEHOLDER
#include "problems/generators/random_problems.h"
