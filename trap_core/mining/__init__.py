"""Plane graphs over time to spatio-temporal patterns (DYPLAGRAM_ST, TRAP_SPEC section 3)."""

from trap_core.mining.auto import mine_auto
from trap_core.mining.errors import MiningError
from trap_core.mining.miner import mine
from trap_core.mining.params import LINKINGS, MiningParams
from trap_core.mining.result import MiningResult
from trap_core.mining.windows import WindowedMiner

__all__ = ["LINKINGS", "MiningError", "MiningParams", "MiningResult", "WindowedMiner", "mine", "mine_auto"]
