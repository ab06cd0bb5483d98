#include "cli/techniques_command.h"

#include <iostream>

namespace so {

int runTechniquesCommand(ListingFormat format) {
    std::cout << techniquesListing(format);
    return 0;
}

}  // namespace so
