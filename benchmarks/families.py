"""The policy families a row trains with lerobot-train: ACT and Diffusion Policy, each its
flags from the recipe. A family is its name, its flags for a first training and its label on
the leaderboard; a DAgger round trains on from the last round's weights and settings."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rows import Recipe

# ACT's default normalizes state, images and actions but not the environment state (the
# bricks, goals and hands): a policy trained so ignored them
ACT_NORMALIZED = {kind: "MEAN_STD" for kind in ("VISUAL", "STATE", "ENV", "ACTION")}
# Diffusion Policy denoises actions clipped to [-1, 1]: its actions and state scaled to that
# range by their bounds (its own default), the environment state too (left raw by default)
DIFFUSION_NORMALIZED = {
    "VISUAL": "MEAN_STD",
    "STATE": "MIN_MAX",
    "ENV": "MIN_MAX",
    "ACTION": "MIN_MAX",
}
LABELS = {"act": "ACT (lerobot-train)", "diffusion": "Diffusion Policy (lerobot-train)"}


def act_flags(r: Recipe) -> list[str]:
    """ACT's: its size, its chunk executed whole, the environment state normalized."""
    return [
        "--policy.type=act",
        f"--policy.dim_model={r.dim_model}",
        f"--policy.n_heads={r.heads}",
        f"--policy.dim_feedforward={r.feedforward}",
        f"--policy.n_encoder_layers={r.encoder_layers}",
        f"--policy.n_decoder_layers={r.decoder_layers}",
        f"--policy.chunk_size={r.chunk}",
        f"--policy.use_vae={str(r.vae).lower()}",
        *(
            [f"--policy.normalization_mapping={json.dumps(ACT_NORMALIZED)}"]
            if r.normalize_environment
            else []
        ),
        f"--policy.n_action_steps={r.action_steps}",
        "--policy.pretrained_backbone_weights=null",
    ]


def diffusion_flags(r: Recipe) -> list[str]:
    """Diffusion Policy's, sized for a CPU: a U-Net of `down_dims` (lerobot's default is
    512-1024-2048), `chunk` actions predicted from
    `obs_steps` observations and `action_steps` of them executed, and DDIM's
    `inference_steps` denoising steps at run time where DDPM takes all 100."""
    normalized = dict(DIFFUSION_NORMALIZED)
    if not r.normalize_environment:
        del normalized["ENV"]
    return [
        "--policy.type=diffusion",
        f"--policy.n_obs_steps={r.obs_steps}",
        f"--policy.horizon={r.chunk}",
        f"--policy.n_action_steps={r.action_steps}",
        # the frames a window may not start in: horizon - n_action_steps - n_obs_steps + 1
        f"--policy.drop_n_last_frames={r.chunk - r.action_steps - r.obs_steps + 1}",
        f"--policy.down_dims={json.dumps(list(r.down_dims))}",
        "--policy.noise_scheduler_type=DDIM",
        f"--policy.num_inference_steps={r.inference_steps}",
        f"--policy.normalization_mapping={json.dumps(normalized)}",
        "--policy.pretrained_backbone_weights=null",
        "--policy.use_group_norm=true",  # no pretrained weights: BatchNorm's wants them
    ]


FLAGS = {"act": act_flags, "diffusion": diffusion_flags}


def first_training(r: Recipe) -> list[str]:
    """The policy's flags for a first training, by the recipe's family."""
    return FLAGS[r.policy](r)
