#include <stdexcept>
#include <string>

#include "gyrostat/integrate/sundials.hpp"

namespace gyrostat::integrate::sundials {

void check(int flag, const char* call) {
    if (flag < 0) throw std::runtime_error(std::string(call) + " failed with flag " + std::to_string(flag));
}

Context::Context() { check(SUNContext_Create(nullptr, &ctx_), "SUNContext_Create"); }
Context::~Context() { SUNContext_Free(&ctx_); }

Vector make_vector(int n, SUNContext ctx) {
    N_Vector v = N_VNew_Serial(n, ctx);
    if (v == nullptr) throw std::runtime_error("N_VNew_Serial failed");
    return Vector(v);
}

void ErrorLog::handler(int error_code, const char* module, const char* function, char* msg, void* data) {
    auto* log = static_cast<ErrorLog*>(data);
    const std::string text = std::string(module) + "::" + function + ": " + msg;
    if (error_code > 0) {  // CV_WARNING / ARK_WARNING: only this one changes what the run reports
        if (text.find("t + h = t") != std::string::npos) log->step_below_resolution = true;
    } else {
        log->last_error = text;
    }
}

}  // namespace gyrostat::integrate::sundials
