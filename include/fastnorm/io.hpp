#pragma once
/// @file io.hpp
/// Module umbrella: files. The `.case` format of one normal problem; the profile files of
/// the wheel–rail layer are read by fastnorm/wheelrail/profile_file.hpp.

#include "fastnorm/case_file.hpp"
