// A fixture of checks/layering_catches_an_internal_include: dynamics/ reaching into volume/.

#include "volume/contact.hpp"
#include "volume/kernels/bvh_cache.hpp"
