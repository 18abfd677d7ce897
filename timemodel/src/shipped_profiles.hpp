// Device profiles compiled into the library from timemodel/profiles/<scene>.json (see
// timemodel/CMakeLists.txt, which generates shipped_profiles.cpp in the build folder).
#pragma once

#include <string>
#include <vector>

namespace lodopt::timemodel {

struct ShippedProfile {
    std::string scene;
    std::string json;
};

const std::vector<ShippedProfile>& shippedProfiles();

}  // namespace lodopt::timemodel
