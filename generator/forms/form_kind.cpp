#include "forms/form_kind.hpp"

namespace rotgen {

const char* to_string(form_kind f) {
    switch (f) {
    case form_kind::lagrangian:
        return "lagrangian";
    case form_kind::hamiltonian:
        return "hamiltonian";
    case form_kind::reduced:
        return "reduced";
    case form_kind::body:
        return "body";
    case form_kind::rotor:
        return "rotor";
    case form_kind::rotor_x:
        return "rotor_x";
    }
    return "?";
}

} // namespace rotgen
