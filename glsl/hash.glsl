// Stateless counter-based randomness (Jarzynski & Olano 2020, PCG hash), integer arithmetic
// only. src/sge/sign_hash.h is its C++ twin; a GL test checks they agree bit for bit.
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// s_i ∈ {−1, +1} for parameter i at perturbation counter c (step × samples + sample).
float perturbationSign(uint parameter, uint counter, uint seed) {
    uint h = pcgHash(parameter ^ pcgHash(counter ^ pcgHash(seed)));
    return (h & 0x80000000u) != 0u ? 1.0 : -1.0;
}
