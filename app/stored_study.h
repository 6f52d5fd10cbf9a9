// Reading a study database that already exists (profiles_db -> the commands): opening it without
// ever writing it, finding a run by name, and a run's stored step read back as the wear loop's
// state (the rails, their damage, each vehicle entry's curving solution and each wearing wheel,
// bit for bit as the step stored them). `railwear history` reads through the first two,
// `railwear wear --resume` continues from the third, and `railwear curving --db` solves a vehicle
// on a stored step's rails from its stored curving.
#pragma once

#include <cstdint>
#include <string>

#include "profiles_db/profile_store.h"
#include "wear/wear_simulation.h"

namespace railwear::app {

// The database at `path`, read-only (ProfileStore::OpenReadOnly: never written, migrated or
// recovered). InputError naming the file when it does not exist, is empty or is not a railwear
// study database.
ProfileStore OpenExistingStudy(const std::string& path);

// The run named `name`; InputError listing the database's runs when there is none.
RunInfo FindRunOrThrow(const ProfileStore& db, const std::string& name);

// Step `step` of run `run` (both must exist: ProfileStore::LoadStep throws otherwise).
WearState StateFromStore(const ProfileStore& store, int64_t run, int step);

}  // namespace railwear::app
