#include "throng/support/SceneOptions.h"

#include "throng/support/Validators.h"

namespace throng::support {

void declareSceneOptions(CLI::App& app, std::string& scene, std::optional<std::int64_t>& actors, std::optional<std::uint64_t>& seed) {
    app.add_option("--scene", scene, "scene file (JSON)")->type_name("FILE")->check(existingFile());
    app.add_option("--actors", actors, "total actors, the scene's groups scaled to it")
        ->type_name("N")
        ->check(wholeNumber(0, 2'000'000))
        ->default_str("the scene's");
    app.add_option("--seed", seed, "random seed")->type_name("N")->check(wholeNumberFrom(0))->default_str("the scene's");
}

}  // namespace throng::support
