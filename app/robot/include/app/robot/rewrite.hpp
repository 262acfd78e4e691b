#pragma once
/// @file A robot file with only its inertial elements changed.

#include <optional>
#include <string>
#include <vector>

#include "app/robot/inertial_xml.hpp"
#include "app/robot/robot_model.hpp"
#include "engine/mass/mass_properties.hpp"

namespace tumble::app::robot {

/// The robot file's text with link i's inertial element replaced by one for `inertials[i]`
/// (in the link's frame), or added just after the link's start tag, on a line of its own at
/// the link's child indentation, when it has none. Links whose entry is unset are left alone,
/// and every byte outside the replaced elements stays as it was. `inertials` has one entry per
/// link. `comments`, when not empty (one per link), are written as XML comments on the line
/// before each new element ("--" in them becomes "- -"). Throws InputError "FILE: link
/// 'NAME': ..." for a link that can take no element.
std::string rewritten_text(const Robot& robot,
                           const std::vector<std::optional<engine::MassProperties>>& inertials,
                           InertialFrame frame, const std::vector<std::string>& comments = {});

}  // namespace tumble::app::robot
