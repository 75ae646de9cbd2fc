#pragma once
// A non-owning reference to something callable, as C++26's std::function_ref: a lambda handed to a
// function that calls it before returning (forEachChunk, ThreadTeam::run) is passed without being
// copied, so no capture list, however long, makes the call allocate (std::function would).

#include <memory>
#include <type_traits>
#include <utility>

namespace throng {

template <class Signature>
class CallableRef;

/// Refers to a callable taking Args... and returning R; the callable must outlive every call.
template <class R, class... Args>
class CallableRef<R(Args...)> {
public:
    /// Refers to `f` (usually a lambda that lives until the end of the caller's full expression).
    template <class F>
        requires(!std::is_same_v<std::remove_cvref_t<F>, CallableRef> && std::is_invocable_r_v<R, F&, Args...>)
    CallableRef(F&& f) noexcept  // NOLINT(google-explicit-constructor): lambdas convert implicitly, as to std::function
        : object_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))),
          call_([](void* object, Args... args) -> R {
              return (*static_cast<std::remove_reference_t<F>*>(object))(std::forward<Args>(args)...);
          }) {}

    /// Calls the callable referred to.
    R operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

private:
    void* object_;
    R (*call_)(void*, Args...);
};

}  // namespace throng
