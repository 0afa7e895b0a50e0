#pragma once
/// @file wheelrail.hpp
/// Umbrella header of the wheel–rail geometry (namespace fastnorm::wheelrail).

#include "fastnorm/wheelrail/profile_value.hpp"
#include "fastnorm/wheelrail/s1002.hpp"
#include "fastnorm/wheelrail/uic60.hpp"
#include "fastnorm/wheelrail/profile_file.hpp"
