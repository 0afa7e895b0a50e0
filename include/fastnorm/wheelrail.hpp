#pragma once
/// @file wheelrail.hpp
/// Umbrella header of the wheel–rail geometry (namespace fastnorm::wheelrail).

#include "fastnorm/wheelrail/profile_value.hpp"
#include "fastnorm/wheelrail/s1002.hpp"
#include "fastnorm/wheelrail/uic60.hpp"
#include "fastnorm/wheelrail/profile_file.hpp"
#include "fastnorm/wheelrail/profile_curve.hpp"
#include "fastnorm/wheelrail/track.hpp"
#include "fastnorm/wheelrail/wheelset.hpp"
#include "fastnorm/wheelrail/contact_search.hpp"
#include "fastnorm/wheelrail/patch.hpp"
#include "fastnorm/wheelrail/creepage.hpp"
#include "fastnorm/wheelrail/undeformed_distance.hpp"
#include "fastnorm/wheelrail/equilibrium.hpp"
#include "fastnorm/wheelrail/wheelset_contact_options.hpp"
#include "fastnorm/wheelrail/wheelset_contact_result.hpp"
#include "fastnorm/wheelrail/patch_creep.hpp"
#include "fastnorm/wheelrail/wheelset_contact.hpp"
#include "fastnorm/wheelrail/setup.hpp"
