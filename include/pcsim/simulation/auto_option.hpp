// A pcsim command-line option that is auto, true or false
// (-pcsim_accuracy_pilot, -pcsim_record_batches): read in an options block,
// so that -help lists it under 'title' (PETSc lists a title once: one each).
#pragma once

#include <cstddef>

namespace pcsim::simulation {

enum class AutoChoice { automatic, on, off };

// The option's value (automatic when not given; a bare name is true);
// InputError naming the option for another value.
AutoChoice read_auto_option(const char* title, const char* name, const char* help);

// A string option read in an options block under 'title' (-help lists it
// with 'shown_default'): false when not given, else its value in 'value'
// (at most size - 1 characters).
bool read_option_string(const char* title, const char* name, const char* help,
                        const char* shown_default, char* value, std::size_t size);

}  // namespace pcsim::simulation
